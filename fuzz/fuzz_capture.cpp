// Target: topdump's capture readers on file bytes (TOPKIT_FUZZ_FORMAT picks
// the reader: pcap (pcap and pcapng, through libpcap), raw, socat, saleae,
// lines), built as fuzz_capture_<format>. The input is opened as a stdio
// stream over its bytes (fmemopen: seekable, as a regular file) and read
// with read_input(), the reader `topdump read -f FORMAT` runs on an opened
// file (read_file() = open_input() + read_input()), then the analyzer is
// finished. Checks: read_input either reads or explains why not; the sink
// sees no more frames than the analyzer counted; every event written as
// JSON Lines is valid JSON; nothing crashes, leaks or hangs.
//
// Speed (see docs/perf/fuzz-speed.md, "Speed"): the libFuzzer build reads at most
// max_len bytes of an input (as libFuzzer cuts seeds to -max_len); each
// line is checked by json_check.hpp's validator, and on a sample of inputs
// (one in 16, chosen from the bytes; every input in replay builds) also by
// nlohmann::json::accept, which must agree. No file per input (a memfd
// written, then opened through /proc/self/fd cost six system calls an
// input: docs/perf/fuzz-speed.md, "Capture and TCP targets (fourth pass)").
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "capture/sources.hpp"
#include "check.hpp"
#include "json_check.hpp"
#include "output/output.hpp"
#include "session/analyzer.hpp"

#ifndef TOPKIT_FUZZ_FORMAT
#error "define TOPKIT_FUZZ_FORMAT (pcap, raw, socat, saleae, lines)"
#endif
#define TOPKIT_STR2(x) #x
#define TOPKIT_STR(x) TOPKIT_STR2(x)

// In namespace topfuzz: fuzz/coverage-ignorelist.txt leaves the harness's
// own branches uninstrumented (they are the check's, not the code under
// test's); what it calls keeps its coverage.
namespace topfuzz {
namespace {

// Writes every event as `topdump read --json` does and checks that each
// line is one valid JSON object (UTF-8 included: input bytes quoted in a
// message once made nlohmann throw, aborting topdump).
class CheckingSink : public topdump::Sink {
 public:
  explicit CheckingSink(bool cross_check) : cross_check_(cross_check) {}
  void frame(const topdump::FrameEvent& e) override {
    ++frames;
    line.clear();
    topdump::write_frame_json(line, e);
    check();
  }
  void garbage(const topdump::GarbageEvent& e) override {
    ++garbage_runs;
    line.clear();
    topdump::write_garbage_json(line, e);
    check();
  }
  void note(const topdump::NoteEvent& e) override {
    ++notes;
    line.clear();
    topdump::write_note_json(line, e);
    check();
  }
  std::uint64_t frames = 0, garbage_runs = 0, notes = 0;

 private:
  void check() {
    FUZZ_CHECK(!line.empty() && line.back() == '\n' && line.find('\n') == line.size() - 1,
               "a JSON line must end in its only newline");
    const std::string_view text = std::string_view(line).substr(0, line.size() - 1);
    const topfuzz::Json v = topfuzz::json_check(text);
    if (v == topfuzz::Json::too_deep || cross_check_) {
      const bool accepted = nlohmann::json::accept(text);
      FUZZ_CHECK(v == topfuzz::Json::too_deep || accepted == (v == topfuzz::Json::valid),
                 std::string("json_check and nlohmann disagree (nlohmann ") +
                     (accepted ? "accepts" : "rejects") + "): " + line);
      FUZZ_CHECK(accepted, "not valid JSON: " + line);
    } else {
      FUZZ_CHECK(v == topfuzz::Json::valid, "not valid JSON: " + line);
    }
  }
  bool cross_check_;
  std::string line;
};

}  // namespace
}  // namespace topfuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  size = topfuzz::capped(size);
  static const topdump::Format format =
      topdump::format_from_string(TOPKIT_STR(TOPKIT_FUZZ_FORMAT)).value();
  // What open_input() makes of a regular file: the stream at byte 0, its
  // size and its first bytes for detection (fmemopen of 0 bytes is a stream
  // at its end, glibc 2.22 and later).
  topdump::Input in;
  in.name = "input";
  in.file = fmemopen(const_cast<std::uint8_t*>(data), size, "rb");
  FUZZ_CHECK(in.file != nullptr, "fmemopen failed");
  in.regular = true;
  in.size = size;
  in.head.assign(reinterpret_cast<const char*>(data), std::min(size, topdump::kInputHead));

#ifdef TOPKIT_LIBFUZZER
  const bool cross_check = topfuzz::sampled(data, size, 4);
#else
  const bool cross_check = true;  // replays are few: every line both ways
#endif
  topfuzz::CheckingSink sink(cross_check);
  topdump::AnalyzerOptions opts;
  topdump::Analyzer a(opts, sink);
  static const topdump::SourceOptions so;  // the ports tables: the same for every input
  std::string error;
  const bool ok = topdump::read_input(in, format, a, so, error);
  FUZZ_CHECK(ok || !error.empty(), "read_input failed without saying why");
  a.finish();
  FUZZ_CHECK(a.frames_seen() >= sink.frames, "more frame events than frames seen");
  return 0;
}
