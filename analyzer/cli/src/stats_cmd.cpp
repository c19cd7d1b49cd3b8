// topdump stats: the statistics of one or more captures.
#include <iostream>
#include <string>
#include <vector>

#include "common.hpp"

namespace topdump {

namespace {

struct StatsCommand {
  std::vector<std::string> files;

  void declare(CLI::App& sub) { sub.add_option("FILE", files, "capture files")->required(); }
  int run(const Common& c) const;
};

int StatsCommand::run(const Common& c) const {
  Setup s;
  if (!setup(c, s)) return 2;
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
  if (show_progress(c)) s.sopts.progress = progress_bar;
  std::vector<InputInfo> inputs;
  s.sopts.on_input = [&](const InputInfo& i) { inputs.push_back(i); };
  for (const auto& f : files) {
    tee.file_ = f == "-" ? "stdin" : f;
    if (std::string err; !read_file(f, s.format, a, s.sopts, err)) {
      error(err);
      return 2;
    }
    a.finish();
  }
  a.note_if_no_frames("no TOP frame found");
  if (c.json) {
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
  return make_command<StatsCommand>(app, CommandId::stats);
}

}  // namespace topdump
