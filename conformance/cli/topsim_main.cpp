// topsim: a stateful TOP gimbal camera on UDP, TCP, a pseudo-terminal or a
// serial port, with seeded fault injection and pcap recording.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fault_arg.hpp"
#include "sim/server.hpp"
#include "top/text.hpp"
#include "topkit/cli.hpp"
#include "topkit/log.hpp"
#include "topkit/model.hpp"

namespace {

constexpr const char* kTool = "topsim";

bool split_host_port(const std::string& s, std::string& host, std::uint16_t& port) {
  const auto colon = s.rfind(':');
  if (colon == std::string::npos) {
    host = s;
    return true;
  }
  host = s.substr(0, colon);
  try {
    const unsigned long p = std::stoul(s.substr(colon + 1));
    if (p > 65535) return false;
    port = static_cast<std::uint16_t>(p);
  } catch (...) {
    return false;
  }
  return !host.empty();
}

// The command line, as parsed.
struct Options {
  std::string model_name = "c12";
  std::string udp, tcp, serial, faults, record;
  bool pty = false, verbose = false, describe = false;
  std::uint64_t seed = 1;
  int reply_port = -1;
  unsigned baud = 115200;
  std::string profile_name = "field", push_order, push_header, reply_order, reply_header;
  std::string yaw_sign, pitch_sign, field_codes;
  // UDP traits and writes (top/device.hpp traits; "": the profile's)
  std::string reply_from, fan_out, duplicate, write_echo;
  // Identity: SkyDroid VER and MOD, Topotek VSN and PA2 ("": the model's defaults)
  std::string fw_version, device_name;
  bool no_tracking = false;
  bool udp_given = false, tcp_given = false;
};

// An option whose value names one of a list. Checked after parsing by the
// shared layer, as --model is (topkit::cli::one_of): one error format,
// "topsim: error: --pitch-sign sideways: not one of normal, inverted", exit 2.
struct Choice {
  std::string option;
  const std::string* value;
  std::vector<std::string> names;
};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : "|") + n;
  return s;
}

// The models and source of a trait, from top::traits(): "sip (field
// evidence of fan-out, see --describe)"; empty for none.
std::string trait_of(top::TraitKind k) {
  std::string models, source;
  for (const top::Trait& t : top::traits()) {
    if (t.kind != k || t.contested) continue;
    source = std::string(top::to_string(t.source));
    for (top::Model m : top::all_models())
      if (t.models & top::model_bit(m))
        models += (models.empty() ? "" : " ") + std::string(top::to_string(m));
  }
  if (models.empty()) return {};
  return models + " (" + source + " evidence of " + std::string(top::to_string(k)) +
         ", see --describe)";
}

// The default of a trait's switch: "the profile's: ephemeral for sip (field
// evidence of ephemeral-reply-port, see --describe), served under --profile
// document and for the other models".
std::string trait_default(top::TraitKind k, const char* field_value, const char* document_value) {
  const std::string of = trait_of(k);
  if (of.empty()) return std::string("default ") + document_value;
  return "default: the profile's, " + std::string(field_value) + " for " + of + ", " +
         document_value + " under --profile document and for the other models";
}

// The options; returns the named-value ones, to check once parsed.
std::vector<Choice> add_options(CLI::App& app, Options& o) {
  app.add_option("--model", o.model_name, top::model_list("|", "|"))->capture_default_str();
  app.add_option("--udp", o.udp,
                 "serve UDP on HOST:PORT (default 127.0.0.1 and the model's port; the default "
                 "transport but for the C20)")
      ->expected(0, 1);
  app.add_option("--tcp", o.tcp,
                 "serve TCP on HOST:PORT (default 127.0.0.1 and the model's port; the default "
                 "transport of the C20)")
      ->expected(0, 1);
  app.add_flag("--pty", o.pty, "serve on a new pseudo-terminal and print its path");
  app.add_option("--serial", o.serial, "serve on a serial device");
  app.add_option("--baud", o.baud, "serial baud rate")->capture_default_str();
  app.add_option("--fault", o.faults, std::string(topsim::fault_usage()));
  app.add_option("--seed", o.seed, "seed of the fault injection")->capture_default_str();
  app.add_option("--record", o.record,
                 "write every frame received and sent: a pcap on UDP and TCP; on a pty or "
                 "serial line, topdump's line log (TX from the client, RX from the device), "
                 "which a pcap cannot tell from UDP");
  app.add_option("--reply-port", o.reply_port,
                 "UDP: the client port replies and pushes go to (default: the model's, 9004 for "
                 "sip as Topotek V1.1.3 names it, none otherwise; 0: none, replies go to the "
                 "asking port)");
  app.add_flag("-v,--verbose", o.verbose,
               "log every datagram received and sent (UDP, TCP, pty, serial) on stderr");
  std::vector<Choice> choices;
  // An option whose value is one of `names` (listed after its help).
  auto choice = [&](const char* name, std::string& value, const std::string& help,
                    std::vector<std::string> names) {
    app.add_option(name, value, help + ": " + joined(names));
    choices.push_back(Choice{name, &value, std::move(names)});
  };
  choice("--profile", o.profile_name,
         "what the device follows (field: field evidence, then the document's examples, then "
         "its rules; document: the document's examples, then its rules)",
         {std::string(top::to_string(top::Profile::field)),
          std::string(top::to_string(top::Profile::document))});
  app.get_option("--profile")->capture_default_str();
  choice("--push-order", o.push_order, "attitude push addresses", {"swapped", "request-order"});
  choice("--push-header", o.push_header, "attitude push header", {"TP", "tp"});
  choice("--reply-order", o.reply_order, "read reply addresses", {"swapped", "request-order"});
  choice("--reply-header", o.reply_header, "read reply header (2-15 data chars)", {"TP", "tp"});
  choice("--yaw-sign", o.yaw_sign,
         "attitude yaw against every yaw command (default: the model's sign traits, each for "
         "the commands its evidence names; see --describe)",
         {"normal", "inverted"});
  choice("--pitch-sign", o.pitch_sign,
         "attitude pitch against every pitch command (default: the model's sign traits)",
         {"normal", "inverted"});
  app.add_option("--fw-version", o.fw_version,
                 "the version SkyDroid VER / Topotek VSN answers (default: SkyDroid V1.0.78, "
                 "the form ArduPilot's SkyDroid driver parses; Topotek 1.6.26.R.D, a real Topotek "
                 "camera's)");
  app.add_option("--model-name", o.device_name,
                 "the model name SkyDroid MOD / Topotek PA2 answers (default the model's: "
                 "C12, SIP)");
  choice("--field-codes", o.field_codes,
         "accept the command values field evidence says the model takes (C13 PTZ)", {"on", "off"});
  choice("--reply-from", o.reply_from,
         "UDP: send replies and pushes from the port served or from a port of its own (" +
             trait_default(top::TraitKind::ephemeral_reply_port, "ephemeral", "served") + ")",
         {"served", "ephemeral"});
  choice("--fan-out", o.fan_out,
         "UDP: send each reply and push to the client port (--reply-port) and to the last "
         "other port that asked, not to the client port alone (" +
             trait_default(top::TraitKind::fan_out, "on", "off") + ")",
         {"on", "off"});
  choice("--duplicate", o.duplicate,
         "UDP: send two copies to the client port (" +
             trait_default(top::TraitKind::duplicate_to_client_port, "on", "off") + ")",
         {"on", "off"});
  choice("--write-echo", o.write_echo,
         "echo every valid write, also those the document gives no answer (default off: each "
         "write answered as the document says, a Topotek write only where it gives a reply "
         "form, as a real unit does: " +
             trait_of(top::TraitKind::silent_writes) + ")",
         {"on", "off"});
  app.add_flag("--no-tracking", o.no_tracking,
               "Topotek: a lens that cannot track (TRC answers state 4)");
  app.add_flag("--describe", o.describe,
               "print the device's traits with their sources (profile, options) and exit");
  return choices;
}

// Each named value given is one of its list, and each fault's name one of
// topsim's faults; false after the message.
bool choices_valid(const CLI::App& app, const std::vector<Choice>& choices,
                   const std::string& faults) {
  for (const Choice& c : choices)
    if (app.count(c.option) > 0 && !topkit::cli::one_of(kTool, c.option, *c.value, c.names))
      return false;
  return topsim::cli::fault_names_valid(kTool, "--fault", faults);
}

// The device's options from the traits given.
topsim::DeviceOptions device_options(const Options& o) {
  topsim::DeviceOptions dopt;
  dopt.profile = *top::profile_from_string(o.profile_name);
  auto order = [](const std::string& v) {
    return v == "swapped" ? top::Order::swapped : top::Order::request_order;
  };
  auto header = [](const std::string& v) {
    return v == "TP" ? top::Header::fixed : top::Header::variable;
  };
  if (!o.push_order.empty()) dopt.push_order = order(o.push_order);
  if (!o.push_header.empty()) dopt.push_header = header(o.push_header);
  if (!o.reply_order.empty()) dopt.reply_order = order(o.reply_order);
  if (!o.reply_header.empty()) dopt.reply_header = header(o.reply_header);
  if (!o.yaw_sign.empty()) dopt.yaw_inverted = o.yaw_sign == "inverted";
  if (!o.pitch_sign.empty()) dopt.pitch_inverted = o.pitch_sign == "inverted";
  if (!o.field_codes.empty()) dopt.field_ptz = o.field_codes == "on";
  if (!o.reply_from.empty()) dopt.ephemeral_reply_port = o.reply_from == "ephemeral";
  if (!o.fan_out.empty()) dopt.fan_out = o.fan_out == "on";
  if (!o.duplicate.empty()) dopt.duplicate = o.duplicate == "on";
  if (!o.write_echo.empty()) dopt.write_echo = o.write_echo == "on";
  dopt.version = o.fw_version;
  dopt.model_name = o.device_name;
  dopt.tracking = !o.no_tracking;
  return dopt;
}

// --fw-version and --model-name fit a one-char length (1-15 printable
// chars, no '#' that would start a frame); false after the message.
bool identity_valid(const Options& o) {
  for (const auto& [name, v] :
       {std::pair{"--fw-version", &o.fw_version}, std::pair{"--model-name", &o.device_name}}) {
    if (v->empty()) continue;
    bool ok = v->size() <= top::max_data_hex;
    for (char c : *v) ok = ok && c > ' ' && c < 0x7F && c != '#';
    if (!ok) {
      spdlog::error("{} {}: 1-15 printable chars without spaces or '#'", name, *v);
      return false;
    }
  }
  return true;
}

// The server's configuration, or the exit status (2) after a message.
std::optional<int> configure(const Options& o, top::Model model, topsim::ServerConfig& cfg) {
  const int chosen = static_cast<int>(o.udp_given) + static_cast<int>(o.tcp_given) +
                     static_cast<int>(o.pty) + static_cast<int>(!o.serial.empty());
  if (chosen > 1) {
    spdlog::error("choose one of --udp, --tcp, --pty, --serial");
    return 2;
  }
  cfg.model = model;
  cfg.device_options = device_options(o);
  cfg.seed = o.seed;
  cfg.record = o.record;
  cfg.baud = o.baud;
  cfg.port = topsim::default_port(model);
  if (o.pty) {
    cfg.kind = topsim::TransportKind::pty;
  } else if (!o.serial.empty()) {
    cfg.kind = topsim::TransportKind::serial;
    cfg.device = o.serial;
  } else {
    cfg.kind = o.tcp_given   ? topsim::TransportKind::tcp
               : o.udp_given ? topsim::TransportKind::udp
                             : topsim::default_transport(model);
    const std::string& spec = cfg.kind == topsim::TransportKind::tcp ? o.tcp : o.udp;
    if (!spec.empty() && !split_host_port(spec, cfg.host, cfg.port)) {
      spdlog::error("{}: expected HOST:PORT", spec);
      return 2;
    }
    if (cfg.kind == topsim::TransportKind::udp && spec.empty())
      cfg.extra_udp_ports = topsim::extra_udp_ports(model);
  }
  if (o.reply_port >= 0) cfg.reply_port = static_cast<std::uint16_t>(o.reply_port);
  if (!o.faults.empty()) {
    std::string err;
    auto f = topsim::parse_faults(o.faults, err);
    if (!f) {
      spdlog::error("--fault: {}", err);
      return 2;
    }
    cfg.faults = *f;
  }
  if (o.verbose) {
    // Each datagram (or chunk of a stream), both ways, bytes escaped.
    cfg.on_traffic = [](const topsim::Traffic& t) {
      spdlog::debug("{} {} {} {} bytes: {}", t.link, t.dir, t.peer, t.bytes.size(),
                    top::escape(t.bytes));
    };
  }
  return std::nullopt;
}

// Where a UDP device's datagrams go: " (replies from port 41234 to port
// 9004 twice and to the last other port that asked)".
std::string udp_routes(const topsim::Server& server) {
  const topsim::UdpTraits t = server.udp_traits();
  const std::uint16_t client = server.client_port();
  const std::string cp = "port " + std::to_string(client) + (t.duplicate ? " twice" : "");
  const std::string to =
      client == 0 ? "the asking port"
      : t.fan_out ? cp + " and to the last other port that asked (the asking port unless it is " +
                        std::to_string(client) + ")"
                  : cp;
  const std::uint16_t from = server.reply_from_port();
  return " (replies " + (from ? "from port " + std::to_string(from) + " " : std::string()) + "to " +
         to + ")";
}

// Serves until SIGINT or SIGTERM; the address served goes to stdout.
int serve(const Options& o, const topsim::ServerConfig& cfg) {
  topsim::Server server(cfg);
  server.stop_on_signals();
  server.restart_on_hangup();
  switch (cfg.kind) {
    case topsim::TransportKind::pty:
      std::printf("%s\n", server.pty_path().c_str());
      std::fflush(stdout);
      spdlog::info("topsim {} on pseudo-terminal {}", o.model_name, server.pty_path());
      break;
    case topsim::TransportKind::serial:
      spdlog::info("topsim {} on serial {} at {} baud", o.model_name, cfg.device, cfg.baud);
      break;
    default:
      std::printf("%s %s:%u\n", cfg.kind == topsim::TransportKind::tcp ? "tcp" : "udp",
                  cfg.host.c_str(), static_cast<unsigned>(server.port()));
      for (std::size_t i = 1; i < server.udp_ports().size(); ++i)
        std::printf("udp %s:%u\n", cfg.host.c_str(), static_cast<unsigned>(server.udp_ports()[i]));
      std::fflush(stdout);
      spdlog::info("topsim {} listening on {} {}:{}{}", o.model_name,
                   cfg.kind == topsim::TransportKind::tcp ? "tcp" : "udp", cfg.host, server.port(),
                   cfg.kind == topsim::TransportKind::tcp ? std::string() : udp_routes(server));
  }
  if (cfg.faults.any()) spdlog::info("faults: {} (seed {})", o.faults, o.seed);
  server.run();
  spdlog::info("{} frames in, {} frames out", server.stats().frames_in.load(),
               server.stats().frames_out.load());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Messages go to stderr ("topsim: error: ..."); stdout carries the address served.
  topkit::cli::use_stderr_log(kTool);
  CLI::App app{
      "topsim: a TOP gimbal camera simulator (SkyDroid C10/C10Pro/C12/C13/C20, Topotek SIP)"};
  topkit::cli::setup_app(app, kTool);
  Options o;
  const std::vector<Choice> choices = add_options(app, o);
  if (int rc = topkit::cli::parse(app, argc, argv); rc >= 0) return rc;
  o.udp_given = app.count("--udp") > 0;
  o.tcp_given = app.count("--tcp") > 0;

  const auto model = topkit::cli::model_arg(kTool, o.model_name);
  if (!model || !choices_valid(app, choices, o.faults) || !identity_valid(o)) return 2;
  if (o.describe) {
    const topsim::Device dev(*model, device_options(o));
    std::printf("topsim %s, profile %s\n", o.model_name.c_str(), o.profile_name.c_str());
    for (const auto& t : dev.describe())
      std::printf("  %-24s %-22s %-17s %s\n", t.name.c_str(), t.value.c_str(), t.source.c_str(),
                  t.evidence.c_str());
    return topkit::cli::close_stdout(kTool, 0);
  }
  topsim::ServerConfig cfg;
  if (auto rc = configure(o, *model, cfg)) return *rc;
  if (o.verbose) spdlog::set_level(spdlog::level::debug);
  try {
    return topkit::cli::close_stdout(kTool, serve(o, cfg));
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
}
