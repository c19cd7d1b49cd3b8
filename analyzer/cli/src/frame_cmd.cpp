// topdump frame: decode frames given as arguments.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "output/escape.hpp"
#include "output/output.hpp"
#include "output/render.hpp"

namespace topdump {

namespace {

class FrameCommand : public topkit::cli::Subcommand {
 public:
  explicit FrameCommand(CLI::App& app)
      : Subcommand(
            app, "frame",
            "Decode frames given as arguments (C escapes \\xNN \\r \\n \\\\ give raw bytes)") {
    add_dialect_model(sub_, dialect_, "auto, skydroid or topotek", model_,
                      "auto, " + top::model_list(", ", " or "));
    sub_->add_flag("--json", json_, "one JSON object per frame found")->default_str("");
    sub_->add_option("FRAME", frames_, "byte streams holding frames")->required();
    sub_->footer(
        "Examples:\n"
        "  topdump frame '#tpUG6wGAYEC78328D'\n"
        "  topdump frame --json '#TPUD2rVER0051\\r\\n#tpDU6rVER0105025D'\n"
        "  topdump frame --dialect topotek '#TPPG2rGIC0040'");
  }
  int run() override;

 private:
  std::string dialect_ = "auto";
  std::string model_ = "auto";
  bool json_ = false;
  std::vector<std::string> frames_;
};

struct Found {
  std::size_t arg;
  top::StreamItem item;
};

int FrameCommand::run() {
  top::Dialect dialect{};
  top::Model model{};
  if (!dialect_and_model(dialect_, model_, dialect, model)) return 2;
  std::vector<Found> found;
  std::vector<std::size_t> frames_per_arg(frames_.size(), 0);
  top::DialectDetector detector;
  if (dialect != top::Dialect::unknown) detector.force(dialect);
  if (model != top::Model::unknown) detector.force(top::dialect_of(model));
  for (std::size_t a = 0; a < frames_.size(); ++a) {
    std::string err;
    auto bytes = unescape(frames_[a], err);
    if (!bytes) {
      error("argument " + std::to_string(a + 1) + ": " + err);
      return 2;
    }
    top::StreamDecoder dec;
    dec.feed(*bytes);
    dec.finish();
    top::StreamItem it;
    while (dec.next(it)) {
      if (it.kind == top::ItemKind::frame) {
        detector.observe(it.frame);
        ++frames_per_arg[a];
      }
      found.push_back(Found{a, std::move(it)});
    }
  }
  int status = 0;
  std::size_t n = 0;
  top::DecodeOptions dopts;
  dopts.model = model;
  for (const Found& x : found) {
    if (x.item.kind == top::ItemKind::garbage) {
      const auto& g = x.item;
      if (g.finding.severity == top::Severity::error) status = 1;
      if (json_) {
        std::string j;
        write_garbage_json(j, x.arg + 1, g);
        std::cout << j;
      } else {
        std::cout << "garbage (argument " << x.arg + 1 << ", bytes " << g.offset << "-"
                  << g.offset + g.length - 1 << "): \"" << escape(g.preview)
                  << (g.length > g.preview.size() ? "..." : "") << "\"\n  "
                  << finding_line(g.finding) << "\n";
      }
      continue;
    }
    const top::Frame& f = x.item.frame;
    dopts.dialect = top::dialect_from_frame(f);
    if (dopts.dialect == top::Dialect::unknown || dialect != top::Dialect::unknown ||
        model != top::Model::unknown)
      dopts.dialect = detector.current();
    top::Decoded d = top::decode(f, dopts);
    if (worst(f, d) == top::Severity::error) status = 1;
    ++n;
    if (json_) {
      std::string j;
      write_frame_json(j, x.arg + 1, x.item.offset, f, d);
      std::cout << j;
    } else {
      std::cout << "frame " << n << " (argument " << x.arg + 1 << ", byte " << x.item.offset
                << "): " << escape(f.raw) << "\n"
                << frame_tree(f, d);
    }
  }
  for (std::size_t a = 0; a < frames_.size(); ++a) {
    if (frames_per_arg[a] == 0) {
      error("argument " + std::to_string(a + 1) + ": no frame found");
      status = 1;
    }
  }
  return status;
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> frame_command(CLI::App& app) {
  return std::make_unique<FrameCommand>(app);
}

}  // namespace topdump
