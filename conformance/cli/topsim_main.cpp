// topsim: a stateful TOP gimbal camera on UDP, TCP, a pseudo-terminal or a
// serial port, with seeded fault injection and pcap recording.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <thread>

#include "sim/server.hpp"
#include "topkit/cli.hpp"

namespace {

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

}  // namespace

int main(int argc, char** argv) {
  // Logs go to stderr; stdout carries results (topsim: the address it serves).
  spdlog::set_default_logger(spdlog::stderr_color_mt("topsim"));
  CLI::App app{
      "topsim: a TOP gimbal camera simulator (SkyDroid C10/C10Pro/C12/C13/C20, Topotek SIP)"};
  topkit::cli::setup_app(app, "topsim");
  std::string model_name = "c12";
  std::string udp, tcp, serial, faults, record;
  bool pty = false, verbose = false;
  std::uint64_t seed = 1;
  int reply_port = -1;
  unsigned baud = 115200;
  app.add_option("--model", model_name, top::model_list("|", "|"))->capture_default_str();
  app.add_option("--udp", udp,
                 "serve UDP on HOST:PORT (default 127.0.0.1 and the model's port; the default "
                 "transport but for the C20)")
      ->expected(0, 1);
  app.add_option("--tcp", tcp,
                 "serve TCP on HOST:PORT (default 127.0.0.1 and the model's port; the default "
                 "transport of the C20)")
      ->expected(0, 1);
  app.add_flag("--pty", pty, "serve on a new pseudo-terminal and print its path");
  app.add_option("--serial", serial, "serve on a serial device");
  app.add_option("--baud", baud, "serial baud rate")->capture_default_str();
  app.add_option("--fault", faults,
                 "faults: drop=P,delay=MS,duplicate=P,bad-checksum=P,header-case=P,no-swap,"
                 "lying-length=P,tmp-quirk,split,garbage=P,hang-on=IDENT; firmware faults (SIGHUP "
                 "restarts the device): crash-on=CLASS,hang-on=CLASS,hang-s=S,slow-on=CLASS,"
                 "slow-ms=MS,answer-corrupt, CLASS = ident:ID|len:N|byte:HH");
  app.add_option("--seed", seed, "seed of the fault injection")->capture_default_str();
  app.add_option("--record", record, "write every frame received and sent to FILE.pcap");
  app.add_option("--reply-port", reply_port,
                 "UDP: send replies to this client port (0: the request's source port; "
                 "default 9004 for sip as the Topotek document says, 0 otherwise)");
  app.add_flag("-v,--verbose", verbose, "log every datagram");
  std::string profile_name = "field", push_order, push_header, reply_order, reply_header;
  std::string yaw_sign, pitch_sign, field_codes;
  bool describe = false;
  app.add_option("--profile", profile_name,
                 "field: follow field evidence, then the document's examples, then its rules; "
                 "document: the document's examples, then its rules")
      ->check(CLI::IsMember({"field", "document"}))
      ->capture_default_str();
  // An option whose value is one of `values`.
  auto choice = [&](const char* name, std::string& value, const char* help,
                    std::vector<std::string> values) {
    app.add_option(name, value, help)->check(CLI::IsMember(std::move(values)));
  };
  choice("--push-order", push_order, "attitude push addresses: swapped|request-order",
         {"swapped", "request-order"});
  choice("--push-header", push_header, "attitude push header: TP|tp", {"TP", "tp"});
  choice("--reply-order", reply_order, "read reply addresses: swapped|request-order",
         {"swapped", "request-order"});
  choice("--reply-header", reply_header, "read reply header (2-15 data chars): TP|tp",
         {"TP", "tp"});
  choice("--yaw-sign", yaw_sign, "attitude yaw against the command: normal|inverted",
         {"normal", "inverted"});
  choice("--pitch-sign", pitch_sign, "attitude pitch against the command: normal|inverted",
         {"normal", "inverted"});
  choice("--field-codes", field_codes,
         "accept the command values field evidence says the model takes (C13 PTZ): "
         "on|off",
         {"on", "off"});
  app.add_flag("--describe", describe,
               "print the device's traits with their sources (profile, options) and exit");
  if (int rc = topkit::cli::parse_or_exit(app, argc, argv); rc >= 0) return rc;

  auto model = top::model_from_string(model_name);
  if (!model || *model == top::Model::unknown) {
    spdlog::error("--model {}: not one of {}", model_name, top::model_list());
    return 2;
  }
  const int chosen = static_cast<int>(app.count("--udp") > 0) +
                     static_cast<int>(app.count("--tcp") > 0) + static_cast<int>(pty) +
                     static_cast<int>(!serial.empty());
  if (chosen > 1) {
    spdlog::error("choose one of --udp, --tcp, --pty, --serial");
    return 2;
  }
  topsim::ServerConfig cfg;
  cfg.model = *model;
  topsim::DeviceOptions& dopt = cfg.device_options;
  dopt.profile = *top::profile_from_string(profile_name);
  auto order = [](const std::string& v) {
    return v == "swapped" ? top::Order::swapped : top::Order::request_order;
  };
  auto header = [](const std::string& v) {
    return v == "TP" ? top::Header::fixed : top::Header::variable;
  };
  if (!push_order.empty()) dopt.push_order = order(push_order);
  if (!push_header.empty()) dopt.push_header = header(push_header);
  if (!reply_order.empty()) dopt.reply_order = order(reply_order);
  if (!reply_header.empty()) dopt.reply_header = header(reply_header);
  if (!yaw_sign.empty()) dopt.yaw_inverted = yaw_sign == "inverted";
  if (!pitch_sign.empty()) dopt.pitch_inverted = pitch_sign == "inverted";
  if (!field_codes.empty()) dopt.field_ptz = field_codes == "on";
  if (describe) {
    const topsim::Device dev(*model, dopt);
    std::printf("topsim %s, profile %s\n", model_name.c_str(), profile_name.c_str());
    for (const auto& t : dev.describe())
      std::printf("  %-24s %-22s %-17s %s\n", t.name.c_str(), t.value.c_str(), t.source.c_str(),
                  t.evidence.c_str());
    return std::fflush(stdout) == 0 && !std::ferror(stdout) ? 0 : 2;
  }
  cfg.seed = seed;
  cfg.record = record;
  cfg.baud = baud;
  cfg.port = topsim::default_port(*model);
  if (pty) {
    cfg.kind = topsim::TransportKind::pty;
  } else if (!serial.empty()) {
    cfg.kind = topsim::TransportKind::serial;
    cfg.device = serial;
  } else {
    cfg.kind = app.count("--tcp")   ? topsim::TransportKind::tcp
               : app.count("--udp") ? topsim::TransportKind::udp
                                    : topsim::default_transport(*model);
    const std::string& spec = cfg.kind == topsim::TransportKind::tcp ? tcp : udp;
    if (!spec.empty() && !split_host_port(spec, cfg.host, cfg.port)) {
      spdlog::error("{}: expected HOST:PORT", spec);
      return 2;
    }
    if (cfg.kind == topsim::TransportKind::udp && spec.empty())
      cfg.extra_udp_ports = topsim::extra_udp_ports(*model);
  }
  cfg.reply_port =
      reply_port >= 0 ? static_cast<std::uint16_t>(reply_port) : top::client_port(*model);
  std::string err;
  if (!faults.empty()) {
    auto f = topsim::parse_faults(faults, err);
    if (!f) {
      spdlog::error("--fault: {}", err);
      return 2;
    }
    cfg.faults = *f;
  }
  if (verbose) spdlog::set_level(spdlog::level::debug);
  try {
    topsim::Server server(cfg);
    server.stop_on_signals();
    server.restart_on_hangup();
    switch (cfg.kind) {
      case topsim::TransportKind::pty:
        std::printf("%s\n", server.pty_path().c_str());
        std::fflush(stdout);
        spdlog::info("topsim {} on pseudo-terminal {}", model_name, server.pty_path());
        break;
      case topsim::TransportKind::serial:
        spdlog::info("topsim {} on serial {} at {} baud", model_name, cfg.device, cfg.baud);
        break;
      default:
        std::printf("%s %s:%u\n", cfg.kind == topsim::TransportKind::tcp ? "tcp" : "udp",
                    cfg.host.c_str(), static_cast<unsigned>(server.port()));
        for (std::size_t i = 1; i < server.udp_ports().size(); ++i)
          std::printf("udp %s:%u\n", cfg.host.c_str(),
                      static_cast<unsigned>(server.udp_ports()[i]));
        std::fflush(stdout);
        spdlog::info(
            "topsim {} listening on {} {}:{}{}", model_name,
            cfg.kind == topsim::TransportKind::tcp ? "tcp" : "udp", cfg.host, server.port(),
            cfg.reply_port ? " (replies to port " + std::to_string(cfg.reply_port) + ")" : "");
    }
    if (cfg.faults.any()) spdlog::info("faults: {} (seed {})", faults, seed);
    server.run();
    spdlog::info("topsim: {} frames in, {} frames out", server.stats().frames_in.load(),
                 server.stats().frames_out.load());
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  return 0;
}
