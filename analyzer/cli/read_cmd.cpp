// topdump read / stats / live / serial.
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
#include "commands.hpp"
#include "output/cut.hpp"
#include "output/output.hpp"

namespace topdump {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop.store(true); }

struct Common {
  std::string dialect = "auto";
  std::string model = "auto";
  std::string format = "auto";
  std::vector<std::uint16_t> ports;
  std::vector<std::string> idents;
  std::vector<std::string> addrs;
  std::string severity;
  std::string from, to;
  std::vector<std::string> findings, mute;
  std::uint64_t count = 0;
  double timeout_ms = 2000;
  bool json = false;
  bool verbose = false;
  std::string csv;
  bool no_progress = false;
};

// "UDP 5000, 9002, ...; TCP 5000": the ports every source scans.
std::string scanned_ports() {
  auto list = [](const std::set<std::uint16_t>& ports) {
    std::string v;
    for (auto p : ports) v += (v.empty() ? "" : ", ") + std::to_string(p);
    return v;
  };
  return "UDP " + list(known_ports(false)) + "; TCP " + list(known_ports(true));
}

// The reorder window of read (--help, docs/topdump-json.md): one second of
// capture time covers TCP reassembly and serial CR/LF holds; a wider one
// costs read --json a fifth of its speed (the held output leaves the
// cache), so an unanswered finding found at the timeout (2 s after its
// request) is beyond its reach.
constexpr std::int64_t kReorderWindowUs = 1'000'000;

void add_common(CLI::App* sub, Common& o, bool outputs, bool ports = true) {
  sub->add_option("--dialect", o.dialect, "auto, skydroid or topotek (forces every conversation)")
      ->check(CLI::IsMember({"auto", "skydroid", "topotek"}));
  sub->add_option("--model", o.model,
                  "auto, " + top::model_list(", ", " or ") + " (unsupported-on-model checks)")
      ->check(model_check());
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
      ->check(CLI::IsMember({"info", "warning", "error"}))
      ->default_str("info");
  sub->add_option("--from", o.from,
                  "only frames at or after this time (ISO-8601, epoch seconds, or +SECONDS after "
                  "the input's first timestamp: +1.5, +1.5s, +200ms)");
  sub->add_option("--to", o.to, "only frames at or before this time (as --from)");
  sub->add_option("--finding", o.findings,
                  "only frames and events with this finding code (comma list, repeatable; "
                  "docs/FINDINGS.md)")
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
  if (outputs) {
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

struct Setup {
  AnalyzerOptions aopts;
  Filter filter;
  SourceOptions sopts;
};

// Turns the options into analyzer settings; false (with a message) on bad usage.
bool setup(const Common& o, Setup& s, std::string& err) {
  if (!dialect_and_model(o.dialect, o.model, s.aopts.dialect, s.aopts.model, err)) return false;
  s.aopts.timeout_us = static_cast<std::int64_t>(o.timeout_ms * 1000);
  for (auto p : o.ports) {
    s.sopts.udp_ports.insert(p);
    s.sopts.tcp_ports.insert(p);
  }
  for (const auto& i : o.idents) {
    if (i.size() != 3) {
      err = "--ident " + i + ": an identifier has three characters";
      return false;
    }
    s.filter.idents.push_back(i);  // matched case-insensitively
  }
  for (const auto& [names, muted] : {std::pair{&o.findings, false}, std::pair{&o.mute, true}})
    for (const auto& n : *names)
      if (!s.filter.add_code(n, muted)) {
        err = std::string(muted ? "--mute " : "--finding ") + n +
              ": no such finding code (docs/FINDINGS.md lists them)";
        return false;
      }
  s.filter.max_frames = o.count;
  s.filter.addrs = o.addrs;
  if (!o.severity.empty()) {
    s.filter.severity_set = true;
    s.filter.min_severity = o.severity == "error"     ? top::Severity::error
                            : o.severity == "warning" ? top::Severity::warning
                                                      : top::Severity::info;
  }
  for (const auto& [name, text, at, rel] :
       {std::tuple{"--from", &o.from, &s.filter.from, &s.filter.from_rel},
        std::tuple{"--to", &o.to, &s.filter.to, &s.filter.to_rel}}) {
    if (text->empty()) continue;
    if (text->front() == '+') {
      auto d = parse_duration(std::string_view(*text).substr(1));
      if (!d) {
        err = std::string(name) + " " + *text + ": not +SECONDS (+1.5, +1.5s, +200ms)";
        return false;
      }
      *rel = *d;
      continue;
    }
    auto t = parse_time(*text);
    if (!t) {
      err = std::string(name) + " " + *text +
            ": not an ISO-8601 time, epoch seconds or +SECONDS after the start";
      return false;
    }
    *at = *t;
  }
  return true;
}

// A source finding on stderr, naming the file once: "topdump: FILE: !! ...",
// the message without its own "FILE: ".
void source_note_to_stderr(const std::string& file, const NoteEvent& e) {
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

// Source findings also go to stderr, naming the file, unless stderr is
// where stdout goes.
class Tee : public Sink {
 public:
  Tee(Sink& inner, std::string file)
      : inner_(inner), file_(std::move(file)), copy_(!stderr_is_stdout()) {}
  void frame(const FrameEvent& e) override { inner_.frame(e); }
  void garbage(const GarbageEvent& e) override { inner_.garbage(e); }
  void note(const NoteEvent& e) override {
    if (!e.conv && copy_) source_note_to_stderr(file_, e);
    inner_.note(e);
  }
  Sink& inner_;
  std::string file_;
  bool copy_;
};

std::unique_ptr<Sink> make_sink(const Common& o, Out& out, std::string& err) {
  if (!o.csv.empty()) {
    std::vector<std::string> cols;
    std::stringstream ss(o.csv);
    std::string c;
    while (std::getline(ss, c, ',')) {
      if (std::string why = csv_column_error(c); !why.empty()) {
        err = "--csv: " + why;
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

int status_of(const Analyzer& a) { return a.worst() == top::Severity::error ? 1 : 0; }

struct ReadOptions {
  Common c;
  std::vector<std::string> files;
  bool say_input = false;
  std::string write;  // -w
};

// The progress bar goes to stderr when it is a terminal and stdout is not
// one: on the same terminal it would mix with the output lines.
bool show_progress(const Common& c) { return !c.no_progress && isatty(2) && !isatty(1); }

int run_read(const ReadOptions& o) {
  Setup s;
  std::string err;
  if (!setup(o.c, s, err)) {
    std::cerr << "topdump read: " << err << "\n";
    return 2;
  }
  auto fmt = format_from_string(o.c.format);
  Out out(stdout, false, kReorderWindowUs);
  auto sink = make_sink(o.c, out, err);
  if (!sink) {
    std::cerr << "topdump read: " << err << "\n";
    return 2;
  }
  const std::string name = o.files.size() == 1 && o.files[0] == "-" ? "stdin" : o.files[0];
  // the summary line on a terminal: stderr, or stdout when only it is one
  std::FILE* summary_to = isatty(2) ? stderr : isatty(1) ? stdout : nullptr;
  std::optional<SummarySink> summary;
  Sink* inner = sink.get();
  if (summary_to) inner = &summary.emplace(*sink);
  std::optional<Cutter> cut;
  if (!o.write.empty()) {
    inner = &cut.emplace(*inner, o.write);
    s.sopts.packet = [&cut](int dlt, std::int64_t ts, std::string_view bytes, std::uint32_t len,
                            std::uint64_t record) { cut->packet(dlt, ts, bytes, len, record); };
  }
  Tee tee(*inner, o.files.size() == 1 ? name : std::string());
  s.aopts.stats = false;
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  if (show_progress(o.c)) s.sopts.progress = progress_bar;
  s.sopts.on_input = [&](const InputInfo& i) {
    if (o.say_input) std::fprintf(stderr, "topdump: %s\n", input_text(i).c_str());
    if (o.c.json && o.c.csv.empty()) {
      write_input_json(out.buf(), i);
      out.done();
    }
  };
  const bool ok = o.files.size() == 2 ? read_merged(o.files, *fmt, a, s.sopts, err, nullptr)
                                      : read_file(o.files[0], *fmt, a, s.sopts, err);
  if (!ok) {
    out.flush();
    std::cerr << "topdump read: " << err << "\n";
    return 2;
  }
  a.finish();
  if (a.frames_seen() == 0)
    a.source_note(kNoTime, ACode::no_frames,
                  (o.files.size() == 1 ? name : name + ", " + o.files[1]) + ": no TOP frame found",
                  0, 0);
  out.flush();
  if (out.failed()) return 2;  // main names the write error
  if (cut && !cut->finish(err)) {
    std::cerr << "topdump read: -w " << err << "\n";
    return 2;
  }
  if (cut && cut->lost())
    std::cerr << "topdump read: -w " << o.write << ": the first packet of " << cut->lost()
              << " frame(s) had left the hold (" << Cutter::kHeldPackets
              << " packets) before the frame was decoded and is not in the file\n";
  if (summary) std::fprintf(summary_to, "%s\n", summary->text().c_str());
  return status_of(a);
}

struct StatsOptions {
  Common c;
  std::vector<std::string> files;
};

int run_stats(const StatsOptions& o) {
  Setup s;
  std::string err;
  if (!setup(o.c, s, err)) {
    std::cerr << "topdump stats: " << err << "\n";
    return 2;
  }
  auto fmt = format_from_string(o.c.format);
  // Nothing shows a frame or a session note: the sink only prints source
  // notes (one virtual call per frame, to the empty Sink::frame).
  struct SourceNotes : Sink {
    void note(const NoteEvent& e) override {
      if (!e.conv) source_note_to_stderr(file_, e);
    }
    std::string file_;
  } tee;
  s.aopts.detail = false;
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  if (show_progress(o.c)) s.sopts.progress = progress_bar;
  std::vector<InputInfo> inputs;
  s.sopts.on_input = [&](const InputInfo& i) { inputs.push_back(i); };
  for (const auto& f : o.files) {
    tee.file_ = f == "-" ? "stdin" : f;
    if (!read_file(f, *fmt, a, s.sopts, err)) {
      std::cerr << "topdump stats: " << err << "\n";
      return 2;
    }
    a.finish();
  }
  if (a.frames_seen() == 0) a.source_note(kNoTime, ACode::no_frames, "no TOP frame found", 0, 0);
  if (o.c.json) {
    std::string j;
    write_stats_json(j, a.stats(), a.worst(), 2, {}, &inputs);
    std::cout << j << "\n";
  } else {
    for (const InputInfo& i : inputs) std::cout << "input: " << input_text(i) << "\n";
    std::cout << stats_text(a.stats(), a.worst());
  }
  return status_of(a);  // main checks that stdout took it all
}

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

struct LiveOptions {
  Common c;
  std::string iface;
  std::vector<std::string> bpf;
};

int run_live(const LiveOptions& o) {
  Setup s;
  std::string err;
  if (!setup(o.c, s, err)) {
    std::cerr << "topdump live: " << err << "\n";
    return 2;
  }
  Out out(stdout, true);
  auto sink = make_sink(o.c, out, err);
  if (!sink) {
    std::cerr << "topdump live: " << err << "\n";
    return 2;
  }
  Tee tee(*sink, o.iface);
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  std::string bpf;
  for (const auto& w : o.bpf) bpf += (bpf.empty() ? "" : " ") + w;
  install_signals();
  bool perm = false;
  if (!capture_live(o.iface, bpf, a, s.sopts, g_stop, err, perm)) {
    std::cerr << "topdump live: " << err << (perm ? " (capturing needs root or CAP_NET_RAW)" : "")
              << "\n";
    return 2;
  }
  a.finish();
  out.flush();
  print_final_stats(o.c, a);
  return status_of(a);
}

struct SerialOptions {
  Common c;
  std::vector<std::string> devices;
  unsigned baud = 115200;
};

int run_serial(const SerialOptions& o) {
  Setup s;
  std::string err;
  if (!setup(o.c, s, err)) {
    std::cerr << "topdump serial: " << err << "\n";
    return 2;
  }
  Out out(stdout, true);
  auto sink = make_sink(o.c, out, err);
  if (!sink) {
    std::cerr << "topdump serial: " << err << "\n";
    return 2;
  }
  Tee tee(*sink, o.devices[0]);
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  install_signals();
  if (!read_serial_ports(o.devices, o.baud, a, g_stop, err)) {
    std::cerr << "topdump serial: " << err << "\n";
    return 2;
  }
  a.finish();
  out.flush();
  print_final_stats(o.c, a);
  return status_of(a);
}

}  // namespace

namespace {

constexpr const char* kFormats = "auto, pcap, pcapng, raw, socat, saleae or lines";

// How read, live and serial print: the text line format, the order, and the
// CSV columns (one list, from the column table).
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

}  // namespace

Run add_read_command(CLI::App& app) {
  auto o = std::make_shared<ReadOptions>();
  CLI::App* sub = app.add_subcommand(
      "read", "Decode a capture: pcap, pcapng, or a serial log (raw, socat, saleae, lines)");
  add_common(sub, o->c, true);
  sub->add_option("--format", o->c.format, kFormats)
      ->check(CLI::IsMember({"auto", "pcap", "pcapng", "raw", "socat", "saleae", "lines"}));
  sub->add_flag("--no-progress", o->c.no_progress,
                "no progress bar (drawn on stderr when it is a terminal and stdout is not)")
      ->default_str("");
  sub->add_flag("-v", o->say_input, "say on stderr what the input was read as (format, link type)")
      ->default_str("");
  sub->add_option("-w,--write", o->write,
                  "also write the packets that carry the selected frames to this capture: "
                  "pcapng when it ends in .pcapng, else pcap; frames of a serial log as "
                  "Ethernet/IPv4/UDP between 127.0.0.1 ports 40001, 40002, ... (one per "
                  "endpoint)");
  sub->add_option("FILE", o->files,
                  "capture file, - for stdin; two serial logs with times (one tap per "
                  "direction) are merged by time into one conversation")
      ->required()
      ->expected(1, 2);
  sub->footer(output_help() +
              "Order: events are printed in capture-time order, across TCP connections and "
              "serial lines, within a reorder window of 1 s of capture time and at most "
              "131072 events; an event that arrives later (an unanswered finding found at "
              "the timeout) is printed ahead of those still held.\n"
              "On a terminal, a summary line (frames, errors, warnings, unanswered, garbage, "
              "time span) ends the output, on stderr.\n"
              "Examples:\n"
              "  topdump read captures/sample.pcap\n"
              "  topdump read -V --ident GAY,ERE captures/sample.pcap\n"
              "  topdump read --json captures/tcp-c10.pcap | jq -r .ident\n"
              "  topdump read --csv n,time,ident,field.pitch,field.pitch.unit "
              "captures/serial-lines.log\n"
              "  topdump read --severity error --from 2024-05-01T12:00:00.5Z capture.pcapng\n"
              "  topdump read --ident gay --from +1.5s -c 20 --mute tp-length capture.pcap\n"
              "  cat capture.pcap | topdump read -\n"
              "  topdump read tx.log rx.log   # two taps of one UART, merged by time\n"
              "  topdump read --ident GAY -w gay.pcap big-capture.pcapng");
  return [o, sub]() { return sub->parsed() ? run_read(*o) : -1; };
}

Run add_stats_command(CLI::App& app) {
  auto o = std::make_shared<StatsOptions>();
  CLI::App* sub = app.add_subcommand("stats", "Statistics of one or more captures");
  add_common(sub, o->c, false);
  sub->add_flag("--json", o->c.json, "one JSON object (docs/topdump-json.md)")->default_str("");
  sub->add_option("--format", o->c.format, kFormats)
      ->check(CLI::IsMember({"auto", "pcap", "pcapng", "raw", "socat", "saleae", "lines"}));
  sub->add_flag("--no-progress", o->c.no_progress,
                "no progress bar (drawn on stderr when it is a terminal and stdout is not)")
      ->default_str("");
  sub->add_option("FILE", o->files, "capture files")->required();
  sub->footer(
      "Examples:\n"
      "  topdump stats captures/sample.pcap\n"
      "  topdump stats --json --ident GAY captures/sample.pcap captures/tcp-c10.pcap");
  return [o, sub]() { return sub->parsed() ? run_stats(*o) : -1; };
}

Run add_live_command(CLI::App& app) {
  auto o = std::make_shared<LiveOptions>();
  CLI::App* sub =
      app.add_subcommand("live", "Decode live traffic on an interface (libpcap); Ctrl-C ends");
  add_common(sub, o->c, true);
  sub->add_option("-i,--interface", o->iface, "interface, e.g. eth0 or lo")->required();
  sub->add_option("BPF", o->bpf, "capture filter, e.g. udp port 5000")->default_str("");
  sub->footer(output_help() +
              "Events are printed as they are decoded; Ctrl-C prints the statistics and ends.\n"
              "Examples:\n"
              "  sudo topdump live -i eth0\n"
              "  sudo topdump live -i lo --json udp port 5000");
  return [o, sub]() { return sub->parsed() ? run_live(*o) : -1; };
}

Run add_serial_command(CLI::App& app) {
  auto o = std::make_shared<SerialOptions>();
  CLI::App* sub =
      app.add_subcommand("serial", "Decode a serial port as bytes arrive (8N1); Ctrl-C ends");
  add_common(sub, o->c, true, false);
  sub->add_option("--baud", o->baud, "baud rate")->check(CLI::Range(50u, 4000000u));
  sub->add_option("DEVICE", o->devices,
                  "serial device, e.g. /dev/ttyUSB0; two devices are two taps of one UART, one "
                  "per direction, read as one conversation")
      ->required()
      ->expected(1, 2);
  sub->footer(output_help() +
              "Events are printed as they are decoded; Ctrl-C prints the statistics and ends.\n"
              "Examples:\n"
              "  topdump serial /dev/ttyUSB0\n"
              "  topdump serial --baud 57600 --model c12 /dev/ttyUSB0\n"
              "  topdump serial /dev/ttyUSB0 /dev/ttyUSB1   # one tap per direction");
  return [o, sub]() { return sub->parsed() ? run_serial(*o) : -1; };
}

}  // namespace topdump
