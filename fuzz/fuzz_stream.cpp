// Target: the stream decoder fed in chunks whose sizes come from the input.
//
// Input: byte 0 = k - 1 in its low 3 bits (k chunk sizes follow), bit 3
// the run (below); then k bytes, each a chunk size 0-255 (cycled; 0 is an
// empty feed); the rest is the stream. The stream is decoded in one piece,
// then in chunks: with bit 3 clear, the items must be the same as in one
// piece; with bit 3 set, flush() follows every chunk (a live link going
// quiet) and the items must still cover every byte. Either way items cover
// every byte exactly once, in order; frames are the stream's bytes at their
// offsets; and the decoder holds no more than a bounded number of bytes,
// whatever the split. The input picks the run as it picks the split, so
// each input pays for two decodes, not three (issue #18); replay builds
// (ctest) make both runs on every input.
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "check.hpp"
#include "mutator.hpp"
#include "reuse.hpp"
#include "top/top.hpp"

using namespace top;
using topfuzz::show;

namespace {

// The decoder may hold a partial frame, or a frame that fails its checksum
// plus a partial frame starting inside it: two maximal frames.
constexpr std::size_t kMaxBuffered = 2 * max_frame_size + 64;

std::string describe(const StreamItem& it) {
  std::string s = it.kind == ItemKind::frame ? "frame" : "garbage";
  s += " @" + std::to_string(it.offset) + "+" + std::to_string(it.length);
  if (it.kind == ItemKind::frame)
    s += " \"" + show(it.frame.raw) + "\" term=" + std::to_string(it.frame.terminator);
  else
    s += " " + std::string(to_string(it.finding.code)) + " \"" + show(it.preview) + "\"";
  return s;
}

bool same_findings(const std::vector<Finding>& a, const std::vector<Finding>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].code != b[i].code || a[i].severity != b[i].severity || a[i].offset != b[i].offset ||
        a[i].message != b[i].message)
      return false;
  return true;
}

bool same_item(const StreamItem& a, const StreamItem& b) {
  if (a.kind != b.kind || a.offset != b.offset || a.length != b.length) return false;
  if (a.kind == ItemKind::garbage)
    return a.preview == b.preview && a.finding.code == b.finding.code &&
           a.finding.offset == b.finding.offset && a.finding.message == b.finding.message;
  const Frame& x = a.frame;
  const Frame& y = b.frame;
  return x.raw == y.raw && x.header == y.header && x.data_offset == y.data_offset &&
         x.data_length == y.data_length && x.terminator == y.terminator &&
         x.checksum_ok == y.checksum_ok && same_findings(x.findings, y.findings);
}

std::vector<StreamItem> items_room() {
  std::vector<StreamItem> v;
#ifdef TOPKIT_LIBFUZZER  // replays (ctest) grow as they need
  v.reserve(topfuzz::capped(std::size_t{1} << 16));
#endif
  return v;
}

void drain(StreamDecoder& d, std::vector<StreamItem>& out) {
  StreamItem it;
  while (d.next(it)) out.push_back(std::move(it));
  FUZZ_CHECK(d.buffered() <= kMaxBuffered,
             "decoder holds " + std::to_string(d.buffered()) + " bytes");
}

// Every byte of the stream belongs to exactly one item (a frame's CR/LF
// terminator belongs to the frame), in order, and frames are the stream's own
// bytes.
void check_cover(std::string_view stream, const std::vector<StreamItem>& items, const char* run) {
  std::uint64_t at = 0;
  for (const StreamItem& it : items) {
    FUZZ_CHECK(it.offset == at, std::string(run) + ": item " + describe(it) +
                                    " does not start where the previous ended (" +
                                    std::to_string(at) + ")");
    FUZZ_CHECK(it.length > 0, std::string(run) + ": empty item " + describe(it));
    at = it.offset + it.length;
    if (it.kind == ItemKind::frame) {
      FUZZ_CHECK(
          it.frame.raw.size() == it.length && stream.substr(it.offset, it.length) == it.frame.raw,
          std::string(run) + ": frame bytes differ from the stream: " + describe(it));
      at += it.frame.terminator;
    }
    FUZZ_CHECK(at <= stream.size(), std::string(run) + ": item past the end: " + describe(it));
  }
  FUZZ_CHECK(at == stream.size(), std::string(run) + ": items cover " + std::to_string(at) +
                                      " of " + std::to_string(stream.size()) + " bytes");
}

// Feeds `stream` to `d` in chunks of the given sizes (cycled), calling
// flush() after each when `flush_each`, then finish(); the items go to `out`.
void feed_chunks(StreamDecoder& d, std::string_view stream, const std::vector<std::size_t>& sizes,
                 bool flush_each, std::vector<StreamItem>& out) {
  std::size_t at = 0, n = 0;
  while (at < stream.size()) {
    const std::size_t len = std::min(sizes[n++ % sizes.size()], stream.size() - at);
    d.feed(stream.substr(at, len));
    if (flush_each) d.flush();
    drain(d, out);
    at += len;
  }
  d.finish();
  drain(d, out);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  size = topfuzz::capped(size);
  if (size < 1) return 0;
  const std::size_t k = (data[0] & 7u) + 1;
  if (size < 1 + k) return 0;
  std::vector<std::size_t> sizes(data + 1, data + 1 + k);
  if (std::all_of(sizes.begin(), sizes.end(), [](std::size_t s) { return s == 0; }))
    sizes.assign(1, 1);
  const std::string_view stream(reinterpret_cast<const char*>(data + 1 + k), size - 1 - k);

  // Kept across inputs (reuse.hpp): each list has room for an item per
  // byte, each decoder is reset.
  static std::vector<StreamItem> whole = items_room(), split = items_room(), flushed = items_room();
  static StreamDecoder d, f;
  const topfuzz::ReleaseAtEnd release(whole, split, flushed);
  d.reset();
  f.reset();
  {
    d.feed(stream);
    drain(d, whole);
    d.finish();
    drain(d, whole);
    FUZZ_CHECK(d.buffered() == 0, "bytes left after finish()");
  }
  check_cover(stream, whole, "one piece");

#ifdef TOPKIT_LIBFUZZER
  const bool flushing = (data[0] & 8u) != 0;
  const bool both = false;
#else
  const bool flushing = false;
  const bool both = true;  // replays are few: every input both ways
#endif
  if (!flushing || both) {
    d.reset();
    feed_chunks(d, stream, sizes, false, split);
    const std::size_t common = std::min(whole.size(), split.size());
    for (std::size_t i = 0; i < common; ++i)
      FUZZ_CHECK(same_item(whole[i], split[i]),
                 "item " + std::to_string(i) + " depends on the split: one piece " +
                     describe(whole[i]) + ", split " + describe(split[i]));
    FUZZ_CHECK(whole.size() == split.size(), "split gives " + std::to_string(split.size()) +
                                                 " items, one piece " +
                                                 std::to_string(whole.size()));
  }
  if (flushing || both) {
    feed_chunks(f, stream, sizes, true, flushed);
    check_cover(stream, flushed, "flushed");
  }
  return 0;
}
