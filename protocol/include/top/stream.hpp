// Stream decoder: turns byte chunks of any size into frames.
//
// Feed chunks with feed(), pull items with next() until it returns false,
// call finish() at the end of the stream and pull again. The items are the
// same however the stream was split. Memory is bounded by max_frame_size
// plus a small look-ahead, whatever the input. Items are decoded one at a
// time as next() asks for them, and their buffers are reused: next() swaps
// the item into `out`, and out's old buffers hold a later item, so a caller
// that keeps one StreamItem decodes without allocating.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "top/detail/ring.hpp"
#include "top/frame.hpp"

namespace top {

enum class ItemKind : std::uint8_t {
  frame,   // a frame; item.frame holds it
  garbage  // bytes that belong to no frame; item.finding says why
};

struct StreamItem {
  ItemKind kind = ItemKind::frame;
  std::uint64_t offset = 0;  // first byte of the frame or garbage
  std::uint64_t length = 0;  // bytes covered (frame without terminator)
  Frame frame;               // kind == frame
  Finding finding;           // kind == garbage: code, offset 0, message
  std::string preview;       // kind == garbage: the first bytes (<= 32)
};

// Exchanges two items (their buffers change hands, nothing is copied).
void swap(StreamItem& a, StreamItem& b) noexcept;

// Records that `count` CR/LF bytes followed a frame: sets its terminator
// (capped at kMaxTerminator) and adds the crlf finding, as the decoder does
// (without its text when `message` is false).
void note_terminator(Frame& f, std::size_t count, bool message = true);

struct StreamOptions {
  // parse.messages false: items carry no texts (findings' and garbage
  // reasons' messages are empty; codes, offsets and lengths are the same).
  ParseOptions parse;
};

class StreamDecoder {
 public:
  explicit StreamDecoder(StreamOptions opts = {});

  // Appends bytes; never fails. Drain next() after each feed: items of the
  // chunk queue up until pulled.
  void feed(std::string_view chunk);
  // Declares the end of the stream: a pending partial frame becomes a
  // truncated garbage item, a held frame is released.
  void finish();
  // Releases a complete frame held to see whether CR/LF follows it (for live
  // links, after each chunk): the frame that ends the bytes fed so far, with
  // the CR/LF bytes among them; a CR/LF fed later is then reported as
  // garbage. It decodes every byte fed so far: their items queue up.
  void flush();
  // For a live link that has gone quiet: flush(), and decide on a frame that
  // fails its checksum with the bytes there are (no longer waiting for the
  // look-ahead that could show another length or a frame starting inside
  // it), and on one whose checksum never came. A frame cut short inside its
  // header or data keeps waiting; the stream stays open.
  void settle();
  // Forgets everything; offsets restart at 0.
  void reset();
  // Moves the next item into `out` (out's old contents are kept for reuse);
  // false when none is ready.
  bool next(StreamItem& out);

  // Bytes fed so far.
  std::uint64_t fed() const noexcept { return base_ + buf_.size(); }
  // Bytes held waiting for more input (bounded by max_frame_size plus the
  // look-ahead, however the input is split).
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

}  // namespace top
