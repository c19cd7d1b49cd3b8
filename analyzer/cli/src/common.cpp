// What read, stats, live and serial share (common.hpp).
#include "common.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "capture/sources.hpp"
#include "output/output.hpp"
#include "topkit/model.hpp"

namespace topdump {

std::atomic<bool> g_stop{false};

namespace {

extern "C" void on_signal(int) { g_stop.store(true); }

// "UDP 5000, 9002, ...; TCP 5000": the ports every source scans.
std::string scanned_ports() {
  auto list = [](const std::set<std::uint16_t>& ports) {
    std::string v;
    for (auto p : ports) v += (v.empty() ? "" : ", ") + std::to_string(p);
    return v;
  };
  return "UDP " + list(known_ports(false)) + "; TCP " + list(known_ports(true));
}

// --dialect, --model, --port, the filters, --timeout-ms and the outputs.
void add_common(CLI::App* sub, Common& o, CommandSpec::Outputs outputs, bool ports) {
  add_dialect_model(sub, o.dialect, "auto, skydroid or topotek (forces every conversation)",
                    o.model,
                    "auto, " + top::model_list(", ", " or ") + " (unsupported-on-model checks)");
  if (ports)
    sub->add_option("--port", o.ports,
                    "another UDP/TCP port that carries TOP (repeatable); always scanned: " +
                        scanned_ports() +
                        "; TCP and UDP on other ports when the payload starts "
                        "like a TOP frame")
        ->allow_extra_args(false)
        ->default_str("");
  sub->add_option("--ident", o.idents,
                  "only frames with these identifiers (comma list, repeatable)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->default_str("");
  sub->add_option("--addr", o.addrs,
                  "only frames from/to this TOP address letter (U M D E P G) or host / host:port")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->default_str("");
  sub->add_option("--severity", o.severity,
                  "only frames whose worst finding is at least this: info (every frame; a frame "
                  "without findings counts as info), warning or error")
      ->default_str("info");
  sub->add_option("--from", o.from,
                  "only frames at or after this time (ISO-8601, epoch seconds, or +SECONDS after "
                  "the input's first timestamp: +1.5, +1.5s, +200ms)");
  sub->add_option("--to", o.to, "only frames at or before this time (as --from)");
  sub->add_option("--finding", o.findings,
                  "only frames and events with this finding code (comma list, repeatable; "
                  "docs/FINDINGS.md; diagnoses: docs/DIAGNOSES.md)")
      ->delimiter(',')
      ->allow_extra_args(false);
  sub->add_option("--mute", o.mute,
                  "drop this finding code everywhere: not shown, counted or in the exit status "
                  "(comma list, repeatable)")
      ->delimiter(',')
      ->allow_extra_args(false);
  sub->add_option("-c,--count", o.count, "stop after this many selected frames (0: all)");
  sub->add_option("--timeout-ms", o.timeout_ms, "a request is unanswered after this long")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            char* end = nullptr;
            const double ms = std::strtod(v.c_str(), &end);
            // at most ten years: microseconds stay well inside 64 bits
            if (end == v.c_str() || *end != 0 || !(ms > 0) || ms > 3.2e11)
              return "--timeout-ms " + v + ": give a number of milliseconds above 0";
            return {};
          },
          "MS"));
  if (outputs == CommandSpec::Outputs::stats) {
    sub->add_flag("--json", o.json, "one JSON object (docs/topdump-json.md)")->default_str("");
  } else {
    auto* json = sub->add_flag("--json", o.json, "JSON Lines (docs/topdump-json.md)");
    auto* verbose = sub->add_flag("-V,--verbose", o.verbose, "the field tree of every frame");
    auto* csv = sub->add_option(
        "--csv", o.csv,
        "CSV with these columns (comma list; field.NAME for a field; the columns are listed "
        "below and in docs/topdump-csv.md)");
    // one output mode: asking for two is a usage error, not a silent choice
    json->excludes(verbose)->excludes(csv);
    verbose->excludes(csv);
    for (auto* f : {json, verbose}) f->default_str("");
  }
}

// --format and --no-progress: the options of the commands that read files.
void add_file_options(CLI::App* sub, Common& o) {
  sub->add_option("--format", o.format, kFormats);
  sub->add_flag("--no-progress", o.no_progress,
                "no progress bar (drawn on stderr when it is a terminal and stdout is not)")
      ->default_str("");
}

// The subcommands with the common options, in CommandId's order: one table
// of what each declares besides its own options, and its --help footer.
const CommandSpec kCommands[] = {
    {"read", "Decode a capture: pcap, pcapng, or a serial log (raw, socat, saleae, lines)",
     CommandSpec::Outputs::events, CommandSpec::Input::files, true,
     "Order: events are printed in capture-time order, across TCP connections and serial lines, "
     "within a reorder window of 1 s of capture time and at most 131072 events; an event that "
     "arrives later (an unanswered finding found at the timeout) is printed ahead of those still "
     "held.\n"
     "On a terminal, a summary line (frames, errors, warnings, unanswered, garbage, time span) "
     "ends the output, on stderr.\n",
     "  topdump read captures/sample.pcap\n"
     "  topdump read -V --ident GAY,ERE captures/sample.pcap\n"
     "  topdump read --json captures/tcp-c10.pcap | jq -r .ident\n"
     "  topdump read --csv n,time,ident,field.pitch,field.pitch.unit captures/serial-lines.log\n"
     "  topdump read --severity error --from 2024-05-01T12:00:00.5Z capture.pcapng\n"
     "  topdump read --ident gay --from +1.5s -c 20 --mute tp-length capture.pcap\n"
     "  cat capture.pcap | topdump read -\n"
     "  topdump read tx.log rx.log   # two taps of one UART, merged by time\n"
     "  topdump read --ident GAY -w gay.pcap big-capture.pcapng"},
    {"stats", "Statistics of one or more captures", CommandSpec::Outputs::stats,
     CommandSpec::Input::files, true, "",
     "  topdump stats captures/sample.pcap\n"
     "  topdump stats --json --ident GAY captures/sample.pcap captures/tcp-c10.pcap"},
    {"live", "Decode live traffic on an interface (libpcap); Ctrl-C ends",
     CommandSpec::Outputs::events, CommandSpec::Input::live, true, "",
     "  sudo topdump live -i eth0\n"
     "  sudo topdump live -i lo --json udp port 5000"},
    {"serial", "Decode a serial port as bytes arrive (8N1); Ctrl-C ends",
     CommandSpec::Outputs::events, CommandSpec::Input::live, false, "",
     "  topdump serial /dev/ttyUSB0\n"
     "  topdump serial --baud 57600 --model c12 /dev/ttyUSB0\n"
     "  topdump serial /dev/ttyUSB0 /dev/ttyUSB1   # one tap per direction"},
};

}  // namespace

void add_taps(CLI::App& sub, const char* name, std::vector<std::string>& inputs,
              const std::string& help) {
  sub.add_option(name, inputs, help)->required()->expected(1, 2);
}

const CommandSpec& spec_of(CommandId id) { return kCommands[static_cast<int>(id)]; }

void declare_common(CLI::App& sub, Common& o, const CommandSpec& spec) {
  add_common(&sub, o, spec.outputs, spec.ports);
  const bool files = spec.input == CommandSpec::Input::files;
  if (files) add_file_options(&sub, o);
  std::string footer;
  if (spec.outputs == CommandSpec::Outputs::events) footer += output_help();
  if (!files)
    footer += "Events are printed as they are decoded; Ctrl-C prints the statistics and ends.\n";
  sub.footer(footer + spec.notes + "Examples:\n" + spec.examples);
}

void add_dialect_model(CLI::App* sub, std::string& dialect, const std::string& dialect_help,
                       std::string& model, const std::string& model_help) {
  sub->add_option("--dialect", dialect, dialect_help);
  sub->add_option("--model", model, model_help);
}

bool dialect_and_model(const std::string& dialect, const std::string& model, top::Dialect& d,
                       top::Model& m) {
  if (!topkit::cli::one_of(kTool, "--dialect", dialect, {"auto", "skydroid", "topotek"}))
    return false;
  std::vector<std::string> models = topkit::cli::model_names();
  models.insert(models.begin(), "auto");
  if (!topkit::cli::one_of(kTool, "--model", model, models)) return false;
  d = *top::dialect_from_string(dialect);
  m = *top::model_from_string(model);
  if (m != top::Model::unknown && d != top::Dialect::unknown && top::dialect_of(m) != d) {
    error("model " + model + " speaks " + std::string(top::to_string(top::dialect_of(m))) +
          ", not " + dialect);
    return false;
  }
  return true;
}

namespace {

// The --from or --to time `text` into `at` or `rel`; false after the message.
bool time_arg(const char* name, const std::string& text, std::int64_t& at, std::int64_t& rel) {
  if (text.empty()) return true;
  if (text.front() == '+') {
    auto d = parse_duration(std::string_view(text).substr(1));
    if (!d) {
      error(std::string(name) + " " + text + ": not +SECONDS (+1.5, +1.5s, +200ms)");
      return false;
    }
    rel = *d;
    return true;
  }
  auto t = parse_time(text);
  if (!t) {
    error(std::string(name) + " " + text +
          ": not an ISO-8601 time, epoch seconds or +SECONDS after the start");
    return false;
  }
  at = *t;
  return true;
}

}  // namespace

bool setup(const Common& o, Setup& s) {
  if (!dialect_and_model(o.dialect, o.model, s.aopts.dialect, s.aopts.model)) return false;
  if (!topkit::cli::one_of(kTool, "--format", o.format, kFormatNames)) return false;
  s.format = *format_from_string(o.format);
  s.aopts.timeout_us = static_cast<std::int64_t>(o.timeout_ms * 1000);
  for (auto p : o.ports) {
    s.sopts.udp_ports.insert(p);
    s.sopts.tcp_ports.insert(p);
  }
  for (const auto& i : o.idents) {
    if (i.size() != 3) {
      error("--ident " + i + ": an identifier has three characters");
      return false;
    }
    s.filter.idents.push_back(i);  // matched case-insensitively
  }
  for (const auto& [names, muted] : {std::pair{&o.findings, false}, std::pair{&o.mute, true}})
    for (const auto& n : *names)
      if (!s.filter.add_code(n, muted)) {
        error(std::string(muted ? "--mute " : "--finding ") + n +
              ": no such finding code (docs/FINDINGS.md and docs/DIAGNOSES.md list them)");
        return false;
      }
  s.filter.max_frames = o.count;
  s.filter.addrs = o.addrs;
  if (!o.severity.empty()) {
    const auto sev =
        topkit::cli::one_of(kTool, "--severity", o.severity, {"info", "warning", "error"});
    if (!sev) return false;
    s.filter.severity_set = true;
    s.filter.min_severity = *sev == 2   ? top::Severity::error
                            : *sev == 1 ? top::Severity::warning
                                        : top::Severity::info;
  }
  return time_arg("--from", o.from, s.filter.from, s.filter.from_rel) &&
         time_arg("--to", o.to, s.filter.to, s.filter.to_rel);
}

// A source finding on stderr, naming the file once: "topdump: FILE: !! ...",
// the message without its own "FILE: ". Only a problem of the input (a
// warning or an error): information about it (a packet the capture
// recorded twice) stays in the output.
void source_note_to_stderr(const std::string& file, const NoteEvent& e) {
  if (e.note.severity == top::Severity::info) return;
  std::string line = note_line(e);
  if (file.empty()) {  // two inputs: the message names its own
    std::fprintf(stderr, "topdump: %s\n", line.c_str());
    return;
  }
  const std::string named = ": " + file + ": ";
  if (auto at = line.find(named); at != std::string::npos) line.erase(at + 2, file.size() + 2);
  std::fprintf(stderr, "topdump: %s: %s\n", file.c_str(), line.c_str());
}

// True when stdout and stderr are the same file or terminal (a copy on
// stderr would print each line twice).
bool stderr_is_stdout() {
  struct stat a {
  }, b{};
  return fstat(1, &a) == 0 && fstat(2, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino &&
         a.st_rdev == b.st_rdev;
}

std::unique_ptr<Sink> make_sink(const Common& o, Out& out) {
  if (!o.csv.empty()) {
    std::vector<std::string> cols;
    std::stringstream ss(o.csv);
    std::string c;
    while (std::getline(ss, c, ',')) {
      if (std::string why = csv_column_error(c); !why.empty()) {
        error("--csv: " + why);
        return nullptr;
      }
      cols.push_back(c);
    }
    return std::make_unique<CsvSink>(out, cols);
  }
  if (o.json) return std::make_unique<JsonSink>(out);
  return std::make_unique<TextSink>(out, o.verbose);
}

void progress_bar(std::uint64_t done, std::uint64_t total) {
  if (total == 0) return;
  int pct = static_cast<int>(done * 100 / total);
  char bar[41];
  int filled = pct * 40 / 100;
  for (int i = 0; i < 40; ++i) bar[i] = i < filled ? '#' : ' ';
  bar[40] = 0;
  std::fprintf(stderr, "\r[%s] %3d%%", bar, pct);
  if (done >= total) std::fprintf(stderr, "\r%*s\r", 48, "");
  std::fflush(stderr);
}

int status_of(const Analyzer& a) {
  return a.worst() == top::Severity::error || a.diagnosed() ? 1 : 0;
}

bool show_progress(const Common& c) { return !c.no_progress && isatty(2) && !isatty(1); }

void install_signals() {
  g_stop.store(false);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

void print_final_stats(const Common& c, const Analyzer& a) {
  if (c.json) {
    std::string j;
    write_stats_json(j, a.stats(), a.worst(), -1, "stats");
    std::cout << j << "\n";
  } else {
    std::cout << "-- statistics\n" << stats_text(a.stats(), a.worst());
  }
  std::cout.flush();
}

int run_live_input(const Common& c, const std::string& name, const Capture& capture) {
  Setup s;
  if (!setup(c, s)) return 2;
  Out out(stdout, true);
  auto sink = make_sink(c, out);
  if (!sink) return 2;
  Tee tee(*sink, name);
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  install_signals();
  if (std::string err; !capture(a, s.sopts, g_stop, err)) {
    error(err);
    return 2;
  }
  a.finish();
  out.flush();
  print_final_stats(c, a);
  return status_of(a);
}

std::string output_help() {
  std::string cols;
  for (const auto& c : csv_columns()) cols += (cols.empty() ? "" : ", ") + c;
  return "Text output, one line per event:\n"
         "  #N TIME TRANSPORT FROM > TO rec R.I@O \"RAW\" IDENT ROLE (TITLE): FIELDS"
         " | reply to #M after X ms | SEVERITY CODE@B: MESSAGE\n"
         "      a frame: N its number; rec R.I@O: record R of the capture (packet, log chunk, "
         "line or CSV row, 1-based), item I in the record (0-based), byte offset O in it; "
         "CODE@B: a finding at byte B of the frame (docs/FINDINGS.md)\n"
         "  -- TIME ... rec R.I@O N bytes \"PREVIEW\" | SEVERITY CODE@B: MESSAGE\n"
         "      bytes that are no frame (garbage), with the finding that says why\n"
         "  !! TIME ... rec R@O SEVERITY CODE: MESSAGE\n"
         "      a finding of the capture, a conversation or a request, not on a frame "
         "(unanswered, tcp-out-of-order, log-syntax, truncated-file, ...); \"-\": no time\n"
         "CSV columns: " +
         cols +
         ", and field.NAME (a decoded field's value without its unit) and field.NAME.unit "
         "(docs/topdump-csv.md).\n";
}

}  // namespace topdump
