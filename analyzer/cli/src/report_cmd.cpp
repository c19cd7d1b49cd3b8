// topdump report CAPTURE... -o report.html | --json
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>

#include "capture/sources.hpp"
#include "common.hpp"
#include "output/output.hpp"
#include "report/report.hpp"

namespace topdump {

namespace {

class ReportCommand : public topkit::cli::Subcommand {
 public:
  explicit ReportCommand(CLI::App& app)
      : Subcommand(app, "report",
                   "A self-contained HTML diagnosis of captures: what went wrong, the gimbal's "
                   "response to "
                   "its commands, latency, streams, findings (docs/REPORT.md)") {
    sub_->add_option("FILE", files_, "capture files (pcap, pcapng, serial logs)")->required();
    sub_->add_option("-o,--output", output_, "write the report here (- for stdout)");
    sub_->add_flag("--json", json_, "the same analysis as one JSON document");
    sub_->add_option("--tolerance", tolerance_,
                     "an angle command has settled when the attitude stays within this many "
                     "degrees of the target")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    add_dialect_model(sub_, dialect_, "auto, skydroid or topotek (forces every conversation)",
                      model_, top::model_list(", ", " or ") + " (ranges and traits)");
    sub_->add_option("--format", format_, "auto, pcap, raw, socat, saleae or lines");
    sub_->add_option("--port", ports_, "another UDP/TCP port that carries TOP (repeatable)")
        ->allow_extra_args(false);
    sub_->add_option("--timeout-ms", timeout_ms_, "a request is unanswered after this long")
        ->check(CLI::PositiveNumber);
    sub_->footer(
        "Examples:\n"
        "  topdump report captures/sample.pcap -o sample.html\n"
        "  topdump report --model c12 --tolerance 0.2 flight.pcapng -o flight.html\n"
        "  topdump report --json captures/tcp-c10.pcap | jq .overview");
  }
  int run() override;

 private:
  std::vector<std::string> files_;
  std::string output_;
  bool json_ = false;
  std::string dialect_ = "auto", model_ = "auto", format_ = "auto";
  std::vector<std::uint16_t> ports_;
  double timeout_ms_ = 2000;
  double tolerance_ = 0.5;
};

// Writes `text` to `path` ("-": stdout); false on any failed write.
bool write_out(const std::string& path, const std::string& text) {
  std::FILE* f = path == "-" ? stdout : std::fopen(path.c_str(), "wb");
  if (!f) return false;
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  ok = (path == "-" ? std::fflush(f) : std::fclose(f)) == 0 && ok;
  return ok;
}

// The report keeps every attitude sample and command of the capture (58 MB
// for the million-frame benchmark capture), and first-touch faults of its
// 4 KiB pages were a sixth of its time. So its heap is grown up front (not
// touched: nothing is committed until used), kept (no trim, no mmap per
// large block), and advised to use transparent huge pages where the kernel
// allows them (THP "madvise" mode): one fault per 2 MiB. Beyond that range
// the heap grows as usual.
void heap_for_bulk() {
  constexpr std::size_t kBlock = 30u << 20, kBlocks = 4;  // under the 32 MiB mmap limit
  if (mallopt(M_MMAP_THRESHOLD, 32 << 20) != 1 || mallopt(M_TRIM_THRESHOLD, 1 << 30) != 1) return;
  const auto base = reinterpret_cast<std::uintptr_t>(sbrk(0));
  void* b[kBlocks];
  for (void*& p : b) p = std::malloc(kBlock);
  for (void* p : b) std::free(p);
  constexpr std::uintptr_t kHuge = 2u << 20;
  const auto lo = (base + kHuge - 1) & ~(kHuge - 1);
  const auto hi = reinterpret_cast<std::uintptr_t>(sbrk(0)) & ~(kHuge - 1);
  if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
}

int ReportCommand::run() {
  top::Dialect dialect{};
  top::Model model{};
  if (!dialect_and_model(dialect_, model_, dialect, model)) return 2;
  if (!topkit::cli::one_of(kTool, "--format", format_, kFormatNames)) return 2;
  if (output_.empty() && !json_) {
    error("give -o FILE.html (or --json)");
    return 2;
  }
  heap_for_bulk();
  AnalyzerOptions aopts;
  aopts.dialect = dialect;
  aopts.model = model;
  aopts.timeout_us = static_cast<std::int64_t>(timeout_ms_ * 1000);
  SourceOptions sopts;
  for (auto p : ports_) {
    sopts.udp_ports.insert(p);
    sopts.tcp_ports.insert(p);
  }
  // Source notes also go to stderr, naming the file.
  struct Sink : report::ReportSink {
    void note(const NoteEvent& e) override {
      if (!e.conv) std::fprintf(stderr, "topdump: %s: %s\n", file.c_str(), note_line(e).c_str());
      report::ReportSink::note(e);
    }
  } sink;
  Analyzer a(aopts, sink);
  std::string err;
  for (const auto& f : files_) {
    sink.file = f;
    if (!read_file(f, *format_from_string(format_), a, sopts, err)) {
      error(err);
      return 2;
    }
    a.finish();
  }
  a.note_if_no_frames("no TOP frame found");
  report::Options ropts;
  ropts.tolerance_deg = tolerance_;
  ropts.files = files_;
  const report::Report r = report::analyze(sink, a.stats(), a.worst(), model, ropts);
  std::string text;
  if (json_)
    report::write_json(text, r);
  else
    report::write_html(text, r);
  const std::string path = output_.empty() ? "-" : output_;
  if (!write_out(path, text)) {
    // run_selected names a failed write to stdout
    if (path != "-") error("cannot write " + path);
    return 2;
  }
  return status_of(a);
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> report_command(CLI::App& app) {
  return std::make_unique<ReportCommand>(app);
}

}  // namespace topdump
