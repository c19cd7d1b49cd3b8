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
#include "commands.hpp"
#include "output/output.hpp"
#include "report/report.hpp"

namespace topdump {

namespace {

struct ReportOptions {
  std::vector<std::string> files;
  std::string output;
  bool json = false;
  std::string dialect = "auto", model = "auto", format = "auto";
  std::vector<std::uint16_t> ports;
  double timeout_ms = 2000;
  double tolerance = 0.5;
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

int run_report(const ReportOptions& o) {
  heap_for_bulk();
  top::Dialect dialect{};
  top::Model model{};
  if (std::string why; !dialect_and_model(o.dialect, o.model, dialect, model, why)) {
    std::cerr << "topdump report: " << why << "\n";
    return 2;
  }
  auto fmt = format_from_string(o.format);
  if (!fmt) {
    std::cerr << "topdump report: bad --format\n";
    return 2;
  }
  if (o.output.empty() && !o.json) {
    std::cerr << "topdump report: give -o FILE.html (or --json)\n";
    return 2;
  }
  AnalyzerOptions aopts;
  aopts.dialect = dialect;
  aopts.model = model;
  aopts.timeout_us = static_cast<std::int64_t>(o.timeout_ms * 1000);
  SourceOptions sopts;
  for (auto p : o.ports) {
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
  for (const auto& f : o.files) {
    sink.file = f;
    if (!read_file(f, *fmt, a, sopts, err)) {
      std::cerr << "topdump report: " << err << "\n";
      return 2;
    }
    a.finish();
  }
  if (a.frames_seen() == 0) a.source_note(kNoTime, ACode::no_frames, "no TOP frame found", 0, 0);
  report::Options ropts;
  ropts.tolerance_deg = o.tolerance;
  ropts.files = o.files;
  const report::Report r = report::analyze(sink, a.stats(), a.worst(), model, ropts);
  std::string text;
  if (o.json)
    report::write_json(text, r);
  else
    report::write_html(text, r);
  const std::string path = o.output.empty() ? "-" : o.output;
  if (!write_out(path, text)) {
    std::cerr << "topdump report: cannot write " << path << "\n";
    return 2;
  }
  return a.worst() == top::Severity::error ? 1 : 0;
}

}  // namespace

Run add_report_command(CLI::App& app) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "A self-contained HTML diagnosis of captures: what went wrong, the gimbal's response to "
      "its commands, latency, streams, findings (docs/REPORT.md)");
  sub->add_option("FILE", o->files, "capture files (pcap, pcapng, serial logs)")->required();
  sub->add_option("-o,--output", o->output, "write the report here (- for stdout)");
  sub->add_flag("--json", o->json, "the same analysis as one JSON document");
  sub->add_option("--tolerance", o->tolerance,
                  "an angle command has settled when the attitude stays within this many "
                  "degrees of the target")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--dialect", o->dialect, "auto, skydroid or topotek (forces every conversation)")
      ->check(CLI::IsMember({"auto", "skydroid", "topotek"}));
  sub->add_option("--model", o->model, top::model_list(", ", " or ") + " (ranges and traits)")
      ->check(model_check());
  sub->add_option("--format", o->format, "auto, pcap, raw, socat, saleae or lines")
      ->check(CLI::IsMember({"auto", "pcap", "pcapng", "raw", "socat", "saleae", "lines"}));
  sub->add_option("--port", o->ports, "another UDP/TCP port that carries TOP (repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--timeout-ms", o->timeout_ms, "a request is unanswered after this long")
      ->check(CLI::PositiveNumber);
  sub->footer(
      "Examples:\n"
      "  topdump report captures/sample.pcap -o sample.html\n"
      "  topdump report --model c12 --tolerance 0.2 flight.pcapng -o flight.html\n"
      "  topdump report --json captures/tcp-c10.pcap | jq .overview");
  return [o, sub]() { return sub->parsed() ? run_report(*o) : -1; };
}

}  // namespace topdump
