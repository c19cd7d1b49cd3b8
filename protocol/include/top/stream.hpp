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
#include <memory>
#include <string>
#include <string_view>

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
  ~StreamDecoder();
  // A copy decodes on from where the original stands. A decoder moved from
  // may only be assigned to or destroyed.
  StreamDecoder(const StreamDecoder& other);
  StreamDecoder& operator=(const StreamDecoder& other);
  StreamDecoder(StreamDecoder&&) noexcept;
  StreamDecoder& operator=(StreamDecoder&&) noexcept;

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
  std::uint64_t fed() const noexcept;
  // Bytes held waiting for more input (bounded by max_frame_size plus the
  // look-ahead, however the input is split).
  std::size_t buffered() const noexcept;

 private:
  class Impl;  // stream.cpp
  std::unique_ptr<Impl> impl_;
};

}  // namespace top
