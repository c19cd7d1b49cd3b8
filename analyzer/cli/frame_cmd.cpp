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

struct FrameOptions {
  std::string dialect = "auto";
  std::string model = "auto";
  bool json = false;
  std::vector<std::string> frames;
};

struct Found {
  std::size_t arg;
  top::StreamItem item;
};

int run_frame(const FrameOptions& o) {
  top::Dialect dialect{};
  top::Model model{};
  if (std::string why; !dialect_and_model(o.dialect, o.model, dialect, model, why)) {
    std::cerr << "topdump frame: " << why << "\n";
    return 2;
  }
  std::vector<Found> found;
  std::vector<std::size_t> frames_per_arg(o.frames.size(), 0);
  top::DialectDetector detector;
  if (dialect != top::Dialect::unknown) detector.force(dialect);
  if (model != top::Model::unknown) detector.force(top::dialect_of(model));
  for (std::size_t a = 0; a < o.frames.size(); ++a) {
    std::string err;
    auto bytes = unescape(o.frames[a], err);
    if (!bytes) {
      std::cerr << "topdump frame: argument " << a + 1 << ": " << err << "\n";
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
      if (o.json) {
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
    if (o.json) {
      std::string j;
      write_frame_json(j, x.arg + 1, x.item.offset, f, d);
      std::cout << j;
    } else {
      std::cout << "frame " << n << " (argument " << x.arg + 1 << ", byte " << x.item.offset
                << "): " << escape(f.raw) << "\n"
                << frame_tree(f, d);
    }
  }
  for (std::size_t a = 0; a < o.frames.size(); ++a) {
    if (frames_per_arg[a] == 0) {
      std::cerr << "topdump frame: argument " << a + 1 << ": no frame found\n";
      status = 1;
    }
  }
  return status;
}

}  // namespace

Run add_frame_command(CLI::App& app) {
  auto o = std::make_shared<FrameOptions>();
  CLI::App* sub = app.add_subcommand(
      "frame", "Decode frames given as arguments (C escapes \\xNN \\r \\n \\\\ give raw bytes)");
  sub->add_option("--dialect", o->dialect, "auto, skydroid or topotek")
      ->check(CLI::IsMember({"auto", "skydroid", "topotek"}));
  sub->add_option("--model", o->model, "auto, " + top::model_list(", ", " or "))
      ->check(model_check());
  sub->add_flag("--json", o->json, "one JSON object per frame found")->default_str("");
  sub->add_option("FRAME", o->frames, "byte streams holding frames")->required();
  sub->footer(
      "Examples:\n"
      "  topdump frame '#tpUG6wGAYEC78328D'\n"
      "  topdump frame --json '#TPUD2rVER0051\\r\\n#tpDU6rVER0105025D'\n"
      "  topdump frame --dialect topotek '#TPPG2rGIC0040'");
  return [o, sub]() { return sub->parsed() ? run_frame(*o) : -1; };
}

}  // namespace topdump
