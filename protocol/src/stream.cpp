#include "top/stream.hpp"

#include <algorithm>
#include <memory>

#include "chars.hpp"
#include "frame_parse.hpp"
#include "swap_members.hpp"
#include "top/detail/ring.hpp"

namespace top {

namespace {
// A garbage run is reported at the latest when it reaches this size, so a
// stream of noise is neither held nor counted forever.
constexpr std::uint64_t kMaxGarbageRun = std::uint64_t{64} * 1024;
constexpr std::size_t kPreview = 32;
// Items decoded ahead of next(): one. A large chunk is decoded lazily, and a
// caller that stops at an item (a fuzz target at the first one that is not a
// clean frame) pays for no more.
constexpr std::size_t kReadyAhead = 1;
// Queue slots kept once the queue is empty again: flush() and settle()
// queue a whole chunk's items, and a long run of noise fed at once comes
// out as several garbage items.
constexpr std::size_t kKeepSlots = 16;
constexpr std::size_t kNoLimit = static_cast<std::size_t>(-1);
// '#' bytes inside a frame that fails its checksum that are tried as the
// start of a valid frame; a cap keeps hostile binary data linear.
constexpr int kMaxInnerCandidates = 16;

// The decoder's state: data only. StreamDecoder's methods and the helpers
// below work on it.
struct Decoding {
  explicit Decoding(StreamOptions o) : opts(o), quiet(o.parse) { quiet.messages = false; }

  StreamOptions opts;
  std::string buf;  // unconsumed bytes live in [pos, size)
  std::size_t pos = 0;
  std::uint64_t base = 0;  // stream offset of buf[0]
  bool at_end = false;
  bool flushing = false;  // inside settle(): judge as at the end, keep the stream open
  // A frame held until we know what follows it: parsed.frame, at stream
  // offset pending_offset.
  bool has_pending = false;
  std::uint64_t pending_offset = 0;
  std::uint64_t pending_length = 0;
  std::uint64_t garbage_start = 0;
  std::uint64_t garbage_len = 0;
  std::string garbage_preview;
  Finding garbage_reason;
  bool garbage_has_reason = false;
  // Items ready for next(). The slots keep their buffers; next() swaps an
  // item out.
  detail::Ring<StreamItem> ready;
  // A complete frame that fails its checksum, held while a frame that
  // starts inside it is still incomplete: its parse and the stream offset of
  // the '#' to try next, so each new chunk costs only that inner parse
  // rather than the whole frame again (which made small chunks quadratic).
  bool has_held = false;
  std::uint64_t held_at = 0;
  std::uint64_t held_scan = 0;
  int held_tried = 0;
  ParseResult held;
  // A frame at stream offset wait_at that cannot be judged before the
  // stream holds wait_until bytes (a serial link feeds a byte at a time:
  // the header is not parsed again for each).
  std::uint64_t wait_at = 0;
  std::uint64_t wait_until = 0;
  // The parse options without messages, the parse at the decoding position
  // (which holds the pending frame) and the parse at a '#' inside a frame
  // (its verdict is all that is used), kept to reuse their buffers.
  ParseOptions quiet;
  ParseResult parsed;
  ParseResult inner;
};

void compact(Decoding& d) {
  if (d.pos == 0) return;
  if (d.pos == d.buf.size()) {
    d.base += d.pos;
    d.buf.clear();
    d.pos = 0;
  } else if (d.pos >= 4096 && d.pos * 2 >= d.buf.size()) {
    d.buf.erase(0, d.pos);
    d.base += d.pos;
    d.pos = 0;
  }
}

void flush_garbage(Decoding& d) {
  if (d.garbage_len == 0) return;
  StreamItem& it = d.ready.push_back();  // a slot whose old buffers are reused
  it.kind = ItemKind::garbage;
  it.offset = d.garbage_start;
  it.length = d.garbage_len;
  reset_keep_capacity(it.frame);
  it.preview.swap(d.garbage_preview);
  const bool text = d.opts.parse.messages;
  if (d.garbage_has_reason) {
    swap(it.finding, d.garbage_reason);
    if (text)
      it.finding.message = detail::cat(
          {std::to_string(d.garbage_len), " byte(s) outside any frame: ", it.finding.message});
  } else {
    it.finding = make_finding(
        FindingCode::garbage, 0,
        text ? detail::cat({std::to_string(d.garbage_len), " byte(s) outside any frame"})
             : std::string());
  }
  d.garbage_len = 0;
  d.garbage_preview.clear();
  d.garbage_has_reason = false;
}

void release_pending(Decoding& d) {
  if (!d.has_pending) return;
  Frame& f = d.parsed.frame;
  note_terminator(f, f.terminator, d.opts.parse.messages);
  StreamItem& it = d.ready.push_back();  // a slot whose old buffers are reused
  it.kind = ItemKind::frame;
  it.offset = d.pending_offset;
  it.length = d.pending_length;
  swap(it.frame, f);  // the next parse takes the slot's old buffers
  it.finding.code = FindingCode{};
  it.finding.severity = Severity{};
  it.finding.offset = 0;
  it.finding.message.clear();
  it.finding.quirk = {};
  it.preview.clear();
  d.has_pending = false;
}

// `why` (when given) is taken: its contents may be exchanged.
void add_garbage(Decoding& d, std::size_t at, std::size_t len, Finding* why) {
  release_pending(d);
  // A run ends at exactly kMaxGarbageRun bytes however the bytes arrived
  // (adding a long span at once used to overshoot the cap, so the items
  // depended on the chunking).
  while (len > 0) {
    std::uint64_t off = d.base + at;
    if (d.garbage_len == 0) {
      d.garbage_start = off;
      d.garbage_preview.clear();
      d.garbage_has_reason = false;
    }
    if (why && !d.garbage_has_reason) {
      swap(d.garbage_reason, *why);
      d.garbage_reason.offset += static_cast<std::uint32_t>(off - d.garbage_start);
      d.garbage_has_reason = true;
    }
    const std::size_t take =
        static_cast<std::size_t>(std::min<std::uint64_t>(len, kMaxGarbageRun - d.garbage_len));
    if (d.garbage_preview.size() < kPreview)
      d.garbage_preview.append(d.buf, at, std::min(take, kPreview - d.garbage_preview.size()));
    d.garbage_len += take;
    at += take;
    len -= take;
    why = nullptr;
    if (d.garbage_len >= kMaxGarbageRun) flush_garbage(d);
  }
}

// What a frame that fails its checksum (`r`, at d.pos) does about the
// '#'s inside it, from `scan_from` with `tried` candidates tried: none
// validates (keep it), one does (its bytes before that one become garbage,
// d.pos moves there), or one needs more bytes (hold the parse: d.held_*).
enum class Inner : std::uint8_t { keep, yielded, wait };
Inner yield_to_inner(Decoding& d, const ParseResult& r, std::string_view all, bool judge,
                     std::size_t scan_from, int tried) {
  const std::string_view outer = all.substr(0, d.pos + r.consumed);
  for (std::size_t q = outer.find('#', scan_from);
       q != std::string_view::npos && tried < kMaxInnerCandidates; q = outer.find('#', q + 1)) {
    ParseResult& inner = d.inner;  // only its verdict is looked at
    parse_frame(all.substr(q), judge, d.quiet, inner);
    if (inner.status == ParseStatus::need_more) {
      // Hold the outer parse; resume at this '#' when more bytes come.
      d.has_held = true;
      d.held_at = d.base + d.pos;
      d.held_scan = d.base + q;
      d.held_tried = tried;
      return Inner::wait;
    }
    ++tried;
    if (inner.status == ParseStatus::frame && inner.frame.checksum_ok) {
      Finding why = make_finding(
          r.frame.has(FindingCode::no_checksum) ? FindingCode::no_checksum
                                                : FindingCode::bad_checksum,
          0,
          d.opts.parse.messages
              ? detail::cat({"abandoned a frame that fails its checksum for a valid frame at +",
                             std::to_string(q - d.pos)})
              : std::string());
      add_garbage(d, d.pos, q - d.pos, &why);
      d.pos = q;
      return Inner::yielded;
    }
  }
  return Inner::keep;
}

void pump(Decoding& d, std::size_t limit) {
  const std::string_view all(d.buf);
  const bool judge = d.at_end || d.flushing;  // parse as if no more bytes came
  while (d.pos < d.buf.size() && d.ready.size() < limit) {
    char c = d.buf[d.pos];
    // A frame's terminator counts up to kMaxTerminator CR/LF bytes; more
    // are garbage after it. (They used to be counted as 255 and covered by no
    // item at all: found by fuzz_stream, regressions/stream/crlf-run-over-255.)
    if (d.has_pending && (c == '\r' || c == '\n') && d.parsed.frame.terminator < kMaxTerminator) {
      ++d.parsed.frame.terminator;
      ++d.pos;
      continue;
    }
    // A frame held may take its second checksum from bytes that came after
    // it (the C10 Pro tool's double checksum): the same frame as in one piece.
    if (d.has_pending && c != '#') {
      const auto second = detail::take_second_checksum(d.parsed.frame, all.substr(d.pos), judge,
                                                       d.opts.parse.messages);
      if (second == detail::SecondChecksum::undecided) break;
      if (second == detail::SecondChecksum::yes) {
        d.pending_length += 2;
        d.pos += 2;
        continue;
      }
    }
    release_pending(d);
    if (c != '#') {
      std::size_t next = d.buf.find('#', d.pos);
      std::size_t end = next == std::string::npos ? d.buf.size() : next;
      add_garbage(d, d.pos, end - d.pos, nullptr);
      d.pos = end;
      continue;
    }
    // The last parse here said nothing changes before this many bytes.
    if (!judge && d.wait_at == d.base + d.pos && d.wait_until > d.base + d.buf.size()) break;
    ParseResult& r = d.parsed;  // its buffers are reused
    std::size_t scan_from = d.pos + 1;
    int tried = 0;
    if (d.has_held && d.held_at == d.base + d.pos) {
      std::swap(r, d.held);
      scan_from = static_cast<std::size_t>(d.held_scan - d.base);
      tried = d.held_tried;
    } else if (d.garbage_len > 0 && d.garbage_has_reason && d.opts.parse.messages) {
      // Inside a garbage run that has its reason: the text of another
      // error would be dropped, so none is written; a frame found here (with
      // findings) is parsed again with its texts.
      parse_frame(all.substr(d.pos), judge, d.quiet, r);
      if (r.status == ParseStatus::frame && !r.frame.findings.empty())
        parse_frame(all.substr(d.pos), judge, d.opts.parse, r);
    } else {
      parse_frame(all.substr(d.pos), judge, d.opts.parse, r);
    }
    d.has_held = false;
    if (r.status == ParseStatus::need_more) {
      d.wait_at = d.base + d.pos;
      d.wait_until = d.base + d.pos + r.consumed;
      break;
    }
    // flushing: a frame cut short is not garbage yet, its rest may come
    if (r.status == ParseStatus::invalid && !d.at_end && r.error.code == FindingCode::truncated)
      break;
    if (r.status == ParseStatus::invalid) {
      std::size_t next = d.buf.find('#', d.pos + 1);
      std::size_t end = next == std::string::npos ? d.buf.size() : next;
      add_garbage(d, d.pos, end - d.pos, &r.error);
      d.pos = end;
      continue;
    }
    // A frame that does not validate yields to a validated frame starting
    // inside it: trust a validated length over an unvalidated one.
    if (!r.frame.checksum_ok) {
      const Inner inner = yield_to_inner(d, r, all, judge, scan_from, tried);
      if (inner == Inner::wait) {
        std::swap(d.held, r);
        break;
      }
      if (inner == Inner::yielded) continue;
    }
    release_pending(d);
    flush_garbage(d);
    // The frame stays in d.parsed until released (every parse comes after
    // release_pending(d)).
    d.pending_offset = d.base + d.pos;
    d.pending_length = r.consumed;
    d.has_pending = true;
    d.pos += r.consumed;
  }
  if (d.at_end && d.pos >= d.buf.size()) {
    release_pending(d);
    flush_garbage(d);
  }
  compact(d);
}

}  // namespace

// The pimpl holds the state only.
class StreamDecoder::Impl : public Decoding {
 public:
  using Decoding::Decoding;
};

void swap(StreamItem& a, StreamItem& b) noexcept {
  detail::swap_members(a, b, &StreamItem::kind, &StreamItem::offset, &StreamItem::length,
                       &StreamItem::frame, &StreamItem::finding, &StreamItem::preview);
}

void note_terminator(Frame& f, std::size_t count, bool message) {
  if (count == 0) return;
  f.terminator = static_cast<std::uint8_t>(std::min(count, kMaxTerminator));
  f.findings.push_back(make_finding(
      FindingCode::crlf, static_cast<std::uint32_t>(f.raw.size()),
      message ? detail::cat({"frame followed by ", std::to_string(f.terminator), " CR/LF byte(s)"})
              : std::string()));
}

void StreamDecoder::reset() {
  Decoding& d = *impl_;
  d.buf.clear();
  d.pos = 0;
  d.base = 0;
  d.at_end = false;
  d.has_pending = false;
  d.garbage_len = 0;
  d.garbage_preview.clear();
  d.garbage_has_reason = false;
  d.ready.clear();
  d.has_held = false;
  d.wait_at = d.wait_until = 0;
}

void StreamDecoder::feed(std::string_view chunk) {
  Decoding& d = *impl_;
  if (d.at_end) return;  // nothing follows the end of a stream
  compact(d);
  d.buf.append(chunk.data(), chunk.size());
}

void StreamDecoder::finish() {
  Decoding& d = *impl_;
  d.at_end = true;
  d.has_held = false;  // judged again with no more bytes to come
}

void StreamDecoder::flush() {
  Decoding& d = *impl_;
  pump(d, kNoLimit);
  release_pending(d);
}

void StreamDecoder::settle() {
  Decoding& d = *impl_;
  // Judge the bytes held as if nothing followed them (a frame that fails its
  // checksum no longer waits for the look-ahead that could show another
  // length or a frame inside it), but keep the stream open: a frame cut
  // short still waits for its rest.
  d.flushing = true;
  pump(d, kNoLimit);
  d.flushing = false;
  release_pending(d);
}

bool StreamDecoder::next(StreamItem& out) {
  Decoding& d = *impl_;
  if (d.ready.empty()) pump(d, kReadyAhead);
  if (d.ready.empty()) return false;
  swap(out, d.ready.front());  // the slot takes out's old buffers, for a later item
  d.ready.pop_front();
  d.ready.trim(kKeepSlots);
  return true;
}

StreamDecoder::StreamDecoder(StreamOptions opts) : impl_(std::make_unique<Impl>(opts)) {}
StreamDecoder::~StreamDecoder() = default;
StreamDecoder::StreamDecoder(const StreamDecoder& other)
    : impl_(std::make_unique<Impl>(*other.impl_)) {}
StreamDecoder& StreamDecoder::operator=(const StreamDecoder& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
StreamDecoder::StreamDecoder(StreamDecoder&&) noexcept = default;
StreamDecoder& StreamDecoder::operator=(StreamDecoder&&) noexcept = default;

std::uint64_t StreamDecoder::fed() const noexcept { return impl_->base + impl_->buf.size(); }
std::size_t StreamDecoder::buffered() const noexcept { return impl_->buf.size() - impl_->pos; }

}  // namespace top
