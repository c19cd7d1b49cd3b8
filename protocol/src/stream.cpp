#include "top/stream.hpp"

#include <algorithm>
#include <memory>

#include "chars.hpp"
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
}  // namespace

// The decoder's state (StreamDecoder forwards to it).
class StreamDecoder::Impl {
 public:
  explicit Impl(StreamOptions opts);
  void feed(std::string_view chunk);
  void finish();
  void flush();
  void settle();
  void reset();
  bool next(StreamItem& out);
  std::uint64_t fed() const noexcept { return base_ + buf_.size(); }
  std::size_t buffered() const noexcept { return buf_.size() - pos_; }

 private:
  // Decodes until `limit` items are ready or the bytes run out.
  void pump(std::size_t limit);
  void release_pending();
  void add_garbage(std::size_t at, std::size_t len, Finding* why);
  void flush_garbage();
  void compact();

  StreamOptions opts_;
  std::string buf_;  // unconsumed bytes live in [pos_, size)
  std::size_t pos_ = 0;
  std::uint64_t base_ = 0;  // stream offset of buf_[0]
  bool at_end_ = false;
  bool flushing_ = false;  // inside settle(): judge as at the end, keep the stream open
  // A frame held until we know what follows it: parsed_.frame, at stream
  // offset pending_offset_.
  bool has_pending_ = false;
  std::uint64_t pending_offset_ = 0;
  std::uint64_t pending_length_ = 0;
  std::uint64_t garbage_start_ = 0;
  std::uint64_t garbage_len_ = 0;
  std::string garbage_preview_;
  Finding garbage_reason_;
  bool garbage_has_reason_ = false;
  // Items ready for next(). The slots keep their buffers; next() swaps an
  // item out.
  detail::Ring<StreamItem> ready_;
  // A complete frame that fails its checksum, held while a frame that
  // starts inside it is still incomplete: its parse and the stream offset of
  // the '#' to try next, so each new chunk costs only that inner parse
  // rather than the whole frame again (which made small chunks quadratic).
  bool has_held_ = false;
  std::uint64_t held_at_ = 0;
  std::uint64_t held_scan_ = 0;
  int held_tried_ = 0;
  ParseResult held_;
  // A frame at stream offset wait_at_ that cannot be judged before the
  // stream holds wait_until_ bytes (a serial link feeds a byte at a time:
  // the header is not parsed again for each).
  std::uint64_t wait_at_ = 0;
  std::uint64_t wait_until_ = 0;
  // The parse options without messages, the parse at the decoding position
  // (which holds the pending frame) and the parse at a '#' inside a frame
  // (its verdict is all that is used), kept to reuse their buffers.
  ParseOptions quiet_;
  ParseResult parsed_;
  ParseResult inner_;
};

StreamDecoder::Impl::Impl(StreamOptions opts) : opts_(opts), quiet_(opts.parse) {
  quiet_.messages = false;
}

void StreamDecoder::Impl::reset() {
  buf_.clear();
  pos_ = 0;
  base_ = 0;
  at_end_ = false;
  has_pending_ = false;
  garbage_len_ = 0;
  garbage_preview_.clear();
  garbage_has_reason_ = false;
  ready_.clear();
  has_held_ = false;
  wait_at_ = wait_until_ = 0;
}

void StreamDecoder::Impl::feed(std::string_view chunk) {
  if (at_end_) return;  // nothing follows the end of a stream
  compact();
  buf_.append(chunk.data(), chunk.size());
}

void StreamDecoder::Impl::finish() {
  at_end_ = true;
  has_held_ = false;  // judged again with no more bytes to come
}

void StreamDecoder::Impl::flush() {
  pump(kNoLimit);
  release_pending();
}

void StreamDecoder::Impl::settle() {
  // Judge the bytes held as if nothing followed them (a frame that fails its
  // checksum no longer waits for the look-ahead that could show another
  // length or a frame inside it), but keep the stream open: a frame cut
  // short still waits for its rest.
  flushing_ = true;
  pump(kNoLimit);
  flushing_ = false;
  release_pending();
}

bool StreamDecoder::Impl::next(StreamItem& out) {
  if (ready_.empty()) pump(kReadyAhead);
  if (ready_.empty()) return false;
  swap(out, ready_.front());  // the slot takes out's old buffers, for a later item
  ready_.pop_front();
  ready_.trim(kKeepSlots);
  return true;
}

void StreamDecoder::Impl::compact() {
  if (pos_ == 0) return;
  if (pos_ == buf_.size()) {
    base_ += pos_;
    buf_.clear();
    pos_ = 0;
  } else if (pos_ >= 4096 && pos_ * 2 >= buf_.size()) {
    buf_.erase(0, pos_);
    base_ += pos_;
    pos_ = 0;
  }
}

void swap(StreamItem& a, StreamItem& b) noexcept {
  using std::swap;
  swap(a.kind, b.kind);
  swap(a.offset, b.offset);
  swap(a.length, b.length);
  swap(a.frame, b.frame);
  swap(a.finding, b.finding);
  a.preview.swap(b.preview);
}

void note_terminator(Frame& f, std::size_t count, bool message) {
  if (count == 0) return;
  f.terminator = static_cast<std::uint8_t>(std::min(count, kMaxTerminator));
  f.findings.push_back(make_finding(
      FindingCode::crlf, static_cast<std::uint32_t>(f.raw.size()),
      message ? detail::cat({"frame followed by ", std::to_string(f.terminator), " CR/LF byte(s)"})
              : std::string()));
}

void StreamDecoder::Impl::release_pending() {
  if (!has_pending_) return;
  Frame& f = parsed_.frame;
  note_terminator(f, f.terminator, opts_.parse.messages);
  StreamItem& it = ready_.push_back();  // a slot whose old buffers are reused
  it.kind = ItemKind::frame;
  it.offset = pending_offset_;
  it.length = pending_length_;
  swap(it.frame, f);  // the next parse takes the slot's old buffers
  it.finding.code = FindingCode{};
  it.finding.severity = Severity{};
  it.finding.offset = 0;
  it.finding.message.clear();
  it.finding.quirk = {};
  it.preview.clear();
  has_pending_ = false;
}

// `why` (when given) is taken: its contents may be exchanged.
void StreamDecoder::Impl::add_garbage(std::size_t at, std::size_t len, Finding* why) {
  release_pending();
  // A run ends at exactly kMaxGarbageRun bytes however the bytes arrived
  // (adding a long span at once used to overshoot the cap, so the items
  // depended on the chunking).
  while (len > 0) {
    std::uint64_t off = base_ + at;
    if (garbage_len_ == 0) {
      garbage_start_ = off;
      garbage_preview_.clear();
      garbage_has_reason_ = false;
    }
    if (why && !garbage_has_reason_) {
      swap(garbage_reason_, *why);
      garbage_reason_.offset += static_cast<std::uint32_t>(off - garbage_start_);
      garbage_has_reason_ = true;
    }
    const std::size_t take =
        static_cast<std::size_t>(std::min<std::uint64_t>(len, kMaxGarbageRun - garbage_len_));
    if (garbage_preview_.size() < kPreview)
      garbage_preview_.append(buf_, at, std::min(take, kPreview - garbage_preview_.size()));
    garbage_len_ += take;
    at += take;
    len -= take;
    why = nullptr;
    if (garbage_len_ >= kMaxGarbageRun) flush_garbage();
  }
}

void StreamDecoder::Impl::flush_garbage() {
  if (garbage_len_ == 0) return;
  StreamItem& it = ready_.push_back();  // a slot whose old buffers are reused
  it.kind = ItemKind::garbage;
  it.offset = garbage_start_;
  it.length = garbage_len_;
  reset_keep_capacity(it.frame);
  it.preview.swap(garbage_preview_);
  const bool text = opts_.parse.messages;
  if (garbage_has_reason_) {
    swap(it.finding, garbage_reason_);
    if (text)
      it.finding.message = detail::cat(
          {std::to_string(garbage_len_), " byte(s) outside any frame: ", it.finding.message});
  } else {
    it.finding = make_finding(
        FindingCode::garbage, 0,
        text ? detail::cat({std::to_string(garbage_len_), " byte(s) outside any frame"})
             : std::string());
  }
  garbage_len_ = 0;
  garbage_preview_.clear();
  garbage_has_reason_ = false;
}

void StreamDecoder::Impl::pump(std::size_t limit) {
  const std::string_view all(buf_);
  const bool judge = at_end_ || flushing_;  // parse as if no more bytes came
  while (pos_ < buf_.size() && ready_.size() < limit) {
    char c = buf_[pos_];
    // A frame's terminator counts up to kMaxTerminator CR/LF bytes; more
    // are garbage after it. (They used to be counted as 255 and covered by no
    // item at all: found by fuzz_stream, regressions/stream/crlf-run-over-255.)
    if (has_pending_ && (c == '\r' || c == '\n') && parsed_.frame.terminator < kMaxTerminator) {
      ++parsed_.frame.terminator;
      ++pos_;
      continue;
    }
    release_pending();
    if (c != '#') {
      std::size_t next = buf_.find('#', pos_);
      std::size_t end = next == std::string::npos ? buf_.size() : next;
      add_garbage(pos_, end - pos_, nullptr);
      pos_ = end;
      continue;
    }
    // The last parse here said nothing changes before this many bytes.
    if (!judge && wait_at_ == base_ + pos_ && wait_until_ > base_ + buf_.size()) break;
    ParseResult& r = parsed_;  // its buffers are reused
    std::size_t scan_from = pos_ + 1;
    int tried = 0;
    if (has_held_ && held_at_ == base_ + pos_) {
      std::swap(r, held_);
      scan_from = static_cast<std::size_t>(held_scan_ - base_);
      tried = held_tried_;
    } else if (garbage_len_ > 0 && garbage_has_reason_ && opts_.parse.messages) {
      // Inside a garbage run that has its reason: the text of another
      // error would be dropped, so none is written; a frame found here (with
      // findings) is parsed again with its texts.
      parse_frame(all.substr(pos_), judge, quiet_, r);
      if (r.status == ParseStatus::frame && !r.frame.findings.empty())
        parse_frame(all.substr(pos_), judge, opts_.parse, r);
    } else {
      parse_frame(all.substr(pos_), judge, opts_.parse, r);
    }
    has_held_ = false;
    if (r.status == ParseStatus::need_more) {
      wait_at_ = base_ + pos_;
      wait_until_ = base_ + pos_ + r.consumed;
      break;
    }
    // flushing: a frame cut short is not garbage yet, its rest may come
    if (r.status == ParseStatus::invalid && !at_end_ && r.error.code == FindingCode::truncated)
      break;
    if (r.status == ParseStatus::invalid) {
      std::size_t next = buf_.find('#', pos_ + 1);
      std::size_t end = next == std::string::npos ? buf_.size() : next;
      add_garbage(pos_, end - pos_, &r.error);
      pos_ = end;
      continue;
    }
    // A frame that does not validate yields to a validated frame starting
    // inside it: trust a validated length over an unvalidated one.
    if (!r.frame.checksum_ok) {
      bool wait = false, yielded = false;
      const std::string_view outer = all.substr(0, pos_ + r.consumed);
      for (std::size_t q = outer.find('#', scan_from);
           q != std::string_view::npos && tried < kMaxInnerCandidates; q = outer.find('#', q + 1)) {
        ParseResult& inner = inner_;  // only its verdict is looked at
        parse_frame(all.substr(q), judge, quiet_, inner);
        if (inner.status == ParseStatus::need_more) {
          // Hold the outer parse; resume at this '#' when more bytes come.
          wait = true;
          has_held_ = true;
          held_at_ = base_ + pos_;
          held_scan_ = base_ + q;
          held_tried_ = tried;
          break;
        }
        ++tried;
        if (inner.status == ParseStatus::frame && inner.frame.checksum_ok) {
          Finding why = make_finding(
              r.frame.has(FindingCode::no_checksum) ? FindingCode::no_checksum
                                                    : FindingCode::bad_checksum,
              0,
              opts_.parse.messages
                  ? detail::cat({"abandoned a frame that fails its checksum for a valid frame at +",
                                 std::to_string(q - pos_)})
                  : std::string());
          add_garbage(pos_, q - pos_, &why);
          pos_ = q;
          yielded = true;
          break;
        }
      }
      if (wait) {
        std::swap(held_, r);
        break;
      }
      if (yielded) continue;
    }
    release_pending();
    flush_garbage();
    // The frame stays in parsed_ until released (every parse comes after
    // release_pending()).
    pending_offset_ = base_ + pos_;
    pending_length_ = r.consumed;
    has_pending_ = true;
    pos_ += r.consumed;
  }
  if (at_end_ && pos_ >= buf_.size()) {
    release_pending();
    flush_garbage();
  }
  compact();
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

void StreamDecoder::feed(std::string_view chunk) { impl_->feed(chunk); }
void StreamDecoder::finish() { impl_->finish(); }
void StreamDecoder::flush() { impl_->flush(); }
void StreamDecoder::settle() { impl_->settle(); }
void StreamDecoder::reset() { impl_->reset(); }
bool StreamDecoder::next(StreamItem& out) { return impl_->next(out); }
std::uint64_t StreamDecoder::fed() const noexcept { return impl_->fed(); }
std::size_t StreamDecoder::buffered() const noexcept { return impl_->buffered(); }

}  // namespace top
