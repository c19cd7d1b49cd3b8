// topdump stats: the statistics of one or more captures.
#include <iostream>
#include <string>
#include <vector>

#include "common.hpp"

namespace topdump {

namespace {

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

}  // namespace

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

}  // namespace topdump
