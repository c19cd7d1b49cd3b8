// topdump read: a capture or two serial logs, decoded event by event.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "common.hpp"
#include "output/cut.hpp"

namespace topdump {

namespace {

struct ReadOptions {
  Common c;
  std::vector<std::string> files;
  bool say_input = false;
  std::string write;  // -w
};

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

}  // namespace topdump
