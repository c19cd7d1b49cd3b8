// Target: topdump's capture readers on file bytes (TOPKIT_FUZZ_FORMAT picks
// the reader: pcap (pcap and pcapng, through libpcap), raw, socat, saleae,
// lines), built as fuzz_capture_<format>. The input is written to an
// in-memory file (memfd) and read with read_file() exactly as `topdump read
// -f FORMAT` reads a file, then the analyzer is finished. Checks: read_file
// either reads or explains why not; the sink sees no more frames than the
// analyzer counted; every event written as JSON Lines is valid
// JSON; nothing crashes, leaks or hangs.
//
// Speed (see README.md, "Speed"): the libFuzzer build reads at most
// max_len bytes of an input (as libFuzzer cuts seeds to -max_len); each
// line is checked by json_check.hpp's validator, and on a sample of inputs
// (one in 16, chosen from the bytes; every input in replay builds) also by
// nlohmann::json::accept, which must agree; big_blocks.hpp recycles any
// block above 128 KiB across inputs (the Analyzer's identifier table was
// one until it became 10 KB pages, README.md "Speed, third pass").
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "analyzer.hpp"
#include "big_blocks.hpp"
#include "check.hpp"
#include "json_check.hpp"
#include "output.hpp"
#include "sources.hpp"

#ifndef TOPKIT_FUZZ_FORMAT
#error "define TOPKIT_FUZZ_FORMAT (pcap, raw, socat, saleae, lines)"
#endif
#define TOPKIT_STR2(x) #x
#define TOPKIT_STR(x) TOPKIT_STR2(x)

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

int memfd() {
  static const int fd = memfd_create("topkit-fuzz-capture", 0);
  return fd;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  topfuzz::big_blocks_next_input();
  size = topfuzz::capped(size);
  static const topdump::Format format =
      topdump::format_from_string(TOPKIT_STR(TOPKIT_FUZZ_FORMAT)).value();
  const int fd = memfd();
  FUZZ_CHECK(fd >= 0, "memfd_create failed");
  FUZZ_CHECK(ftruncate(fd, 0) == 0, "ftruncate failed");
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = pwrite(fd, data + done, size - done, static_cast<off_t>(done));
    FUZZ_CHECK(n > 0, "pwrite failed");
    done += static_cast<std::size_t>(n);
  }
  const std::string path = "/proc/self/fd/" + std::to_string(fd);

#ifdef TOPKIT_LIBFUZZER
  const bool cross_check = topfuzz::sampled(data, size, 4);
#else
  const bool cross_check = true;  // replays are few: every line both ways
#endif
  CheckingSink sink(cross_check);
  topdump::AnalyzerOptions opts;
  topdump::Analyzer a(opts, sink);
  topdump::SourceOptions so;
  std::string error;
  const bool ok = topdump::read_file(path, format, a, so, error);
  FUZZ_CHECK(ok || !error.empty(), "read_file failed without saying why");
  a.finish();
  FUZZ_CHECK(a.frames_seen() >= sink.frames, "more frame events than frames seen");
  return 0;
}
