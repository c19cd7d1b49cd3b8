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

class ReadCommand : public CommonCommand {
 public:
  explicit ReadCommand(CLI::App& app)
      : CommonCommand(
            app, "read",
            "Decode a capture: pcap, pcapng, or a serial log (raw, socat, saleae, lines)") {
    add_common(sub_, c_, true);
    add_file_options(sub_, c_);
    sub_->add_flag("-v", say_input_, "say on stderr what the input was read as (format, link type)")
        ->default_str("");
    sub_->add_option("-w,--write", write_,
                     "also write the packets that carry the selected frames to this capture: "
                     "pcapng when it ends in .pcapng, else pcap; frames of a serial log as "
                     "Ethernet/IPv4/UDP between 127.0.0.1 ports 40001, 40002, ... (one per "
                     "endpoint)");
    sub_->add_option("FILE", files_,
                     "capture file, - for stdin; two serial logs with times (one tap per "
                     "direction) are merged by time into one conversation")
        ->required()
        ->expected(1, 2);
    sub_->footer(output_help() +
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
  }
  int run() override;

 private:
  std::vector<std::string> files_;
  bool say_input_ = false;
  std::string write_;  // -w
};

int ReadCommand::run() {
  Setup s;
  if (!setup(c_, s)) return 2;
  Out out(stdout, false, kReorderWindowUs);
  auto sink = make_sink(c_, out);
  if (!sink) return 2;
  const std::string name = files_.size() == 1 && files_[0] == "-" ? "stdin" : files_[0];
  // the summary line on a terminal: stderr, or stdout when only it is one
  std::FILE* summary_to = isatty(2) ? stderr : isatty(1) ? stdout : nullptr;
  std::optional<SummarySink> summary;
  Sink* inner = sink.get();
  if (summary_to) inner = &summary.emplace(*sink);
  std::optional<Cutter> cut;
  if (!write_.empty()) {
    inner = &cut.emplace(*inner, write_);
    s.sopts.packet = [&cut](int dlt, std::int64_t ts, std::string_view bytes, std::uint32_t len,
                            std::uint64_t record) { cut->packet(dlt, ts, bytes, len, record); };
  }
  Tee tee(*inner, files_.size() == 1 ? name : std::string());
  s.aopts.stats = false;
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  if (show_progress(c_)) s.sopts.progress = progress_bar;
  s.sopts.on_input = [&](const InputInfo& i) {
    if (say_input_) std::fprintf(stderr, "topdump: %s\n", input_text(i).c_str());
    if (c_.json && c_.csv.empty()) {
      write_input_json(out.buf(), i);
      out.done();
    }
  };
  std::string err;
  const bool ok = files_.size() == 2 ? read_merged(files_, s.format, a, s.sopts, err, nullptr)
                                     : read_file(files_[0], s.format, a, s.sopts, err);
  if (!ok) {
    out.flush();
    error(err);
    return 2;
  }
  a.finish();
  if (a.frames_seen() == 0)
    a.source_note(kNoTime, ACode::no_frames,
                  (files_.size() == 1 ? name : name + ", " + files_[1]) + ": no TOP frame found", 0,
                  0);
  out.flush();
  if (out.failed()) return 2;  // run_selected names the write error
  if (cut && !cut->finish(err)) {
    error("-w " + err);
    return 2;
  }
  if (cut && cut->lost())
    topkit::cli::warning(
        kTool, "-w " + write_ + ": the first packet of " + std::to_string(cut->lost()) +
                   " frame(s) had left the hold (" + std::to_string(Cutter::kHeldPackets) +
                   " packets) before the frame was decoded and is not in the file");
  if (summary) std::fprintf(summary_to, "%s\n", summary->text().c_str());
  return status_of(a);
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> read_command(CLI::App& app) {
  return std::make_unique<ReadCommand>(app);
}

}  // namespace topdump
