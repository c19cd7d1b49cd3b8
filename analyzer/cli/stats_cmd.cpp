// topdump stats: the statistics of one or more captures.
#include <iostream>
#include <string>
#include <vector>

#include "common.hpp"

namespace topdump {

namespace {

class StatsCommand : public CommonCommand {
 public:
  explicit StatsCommand(CLI::App& app)
      : CommonCommand(app, "stats", "Statistics of one or more captures") {
    add_common(sub_, c_, false);
    sub_->add_flag("--json", c_.json, "one JSON object (docs/topdump-json.md)")->default_str("");
    add_file_options(sub_, c_);
    sub_->add_option("FILE", files_, "capture files")->required();
    sub_->footer(
        "Examples:\n"
        "  topdump stats captures/sample.pcap\n"
        "  topdump stats --json --ident GAY captures/sample.pcap captures/tcp-c10.pcap");
  }
  int run() override;

 private:
  std::vector<std::string> files_;
};

int StatsCommand::run() {
  Setup s;
  if (!setup(c_, s)) return 2;
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
  if (show_progress(c_)) s.sopts.progress = progress_bar;
  std::vector<InputInfo> inputs;
  s.sopts.on_input = [&](const InputInfo& i) { inputs.push_back(i); };
  for (const auto& f : files_) {
    tee.file_ = f == "-" ? "stdin" : f;
    if (std::string err; !read_file(f, s.format, a, s.sopts, err)) {
      error(err);
      return 2;
    }
    a.finish();
  }
  if (a.frames_seen() == 0) a.source_note(kNoTime, ACode::no_frames, "no TOP frame found", 0, 0);
  if (c_.json) {
    std::string j;
    write_stats_json(j, a.stats(), a.worst(), 2, {}, &inputs);
    std::cout << j << "\n";
  } else {
    for (const InputInfo& i : inputs) std::cout << "input: " << input_text(i) << "\n";
    std::cout << stats_text(a.stats(), a.worst());
  }
  return status_of(a);  // run_selected checks that stdout took it all
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> stats_command(CLI::App& app) {
  return std::make_unique<StatsCommand>(app);
}

}  // namespace topdump
