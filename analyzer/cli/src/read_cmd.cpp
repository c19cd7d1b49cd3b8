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

struct ReadCommand {
  std::vector<std::string> files;
  bool say_input = false;
  std::string write;  // -w

  void declare(CLI::App& sub) {
    sub.add_flag("-v", say_input, "say on stderr what the input was read as (format, link type)")
        ->default_str("");
    sub.add_option("-w,--write", write,
                   "also write the packets that carry the selected frames to this capture: "
                   "pcapng when it ends in .pcapng, else pcap; frames of a serial log as "
                   "Ethernet/IPv4/UDP between 127.0.0.1 ports 40001, 40002, ... (one per "
                   "endpoint)");
    add_taps(sub, "FILE", files,
             "capture file, - for stdin; two serial logs with times (one tap per direction) are "
             "merged by time into one conversation");
  }
  int run(const Common& c) const;
};

int ReadCommand::run(const Common& c) const {
  Setup s;
  if (!setup(c, s)) return 2;
  Out out(stdout, false, kReorderWindowUs);
  auto sink = make_sink(c, out);
  if (!sink) return 2;
  const std::string name = files.size() == 1 && files[0] == "-" ? "stdin" : files[0];
  // the summary line on a terminal: stderr, or stdout when only it is one
  std::FILE* summary_to = isatty(2) ? stderr : isatty(1) ? stdout : nullptr;
  std::optional<SummarySink> summary;
  Sink* inner = sink.get();
  if (summary_to) inner = &summary.emplace(*sink);
  std::optional<Cutter> cut;
  if (!write.empty()) {
    inner = &cut.emplace(*inner, write);
    s.sopts.packet = [&cut](int dlt, std::int64_t ts, std::string_view bytes, std::uint32_t len,
                            std::uint64_t record) { cut->packet(dlt, ts, bytes, len, record); };
  }
  Tee tee(*inner, files.size() == 1 ? name : std::string());
  s.aopts.stats = false;
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  if (show_progress(c)) s.sopts.progress = progress_bar;
  s.sopts.on_input = [&](const InputInfo& i) {
    if (say_input) std::fprintf(stderr, "topdump: %s\n", input_text(i).c_str());
    if (c.json && c.csv.empty()) {
      write_input_json(out.buf(), i);
      out.done();
    }
  };
  std::string err;
  const bool ok = files.size() == 2 ? read_merged(files, s.format, a, s.sopts, err, nullptr)
                                    : read_file(files[0], s.format, a, s.sopts, err);
  if (!ok) {
    out.flush();
    error(err);
    return 2;
  }
  a.finish();
  a.note_if_no_frames((files.size() == 1 ? name : name + ", " + files[1]) + ": no TOP frame found");
  out.flush();
  if (out.failed()) return 2;  // run_selected names the write error
  if (cut && !cut->finish(err)) {
    error("-w " + err);
    return 2;
  }
  if (cut && cut->lost())
    topkit::cli::warning(
        kTool, "-w " + write + ": the first packet of " + std::to_string(cut->lost()) +
                   " frame(s) had left the hold (" + std::to_string(Cutter::kHeldPackets) +
                   " packets) before the frame was decoded and is not in the file");
  if (summary) std::fprintf(summary_to, "%s\n", summary->text().c_str());
  return status_of(a);
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> read_command(CLI::App& app) {
  return make_command<ReadCommand>(app, CommandId::read);
}

}  // namespace topdump
