// The session's events: a decoded frame, a run of garbage, a finding, each
// with where it sits in the capture; and the Sink that receives them (the
// outputs).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "capture/sink.hpp"
#include "diagnoses/cause.hpp"
#include "findings/afindings.hpp"
#include "top/top.hpp"

namespace topdump {

struct Conversation;

// Where a frame sits in the capture.
struct Position {
  std::uint64_t record = 0;  // 1-based record (packet, log chunk, line, CSV row)
  std::uint32_t index = 0;   // 0-based index among the items of the record
  std::uint64_t offset = 0;  // byte offset of the first byte in the record
};

// A finding of the session or source layer.
struct Note {
  ACode code{};
  top::Severity severity{};
  std::string message;
  std::uint64_t frame = 0;  // the frame it is about (0: none)
  // The identifier and TOP addresses of what it is about (a request, a
  // stream), for the filter; zero when it is about no frame (TCP, files).
  char ident[3] = {};
  char src = 0, dst = 0;
  Cause cause = Cause::none;  // unanswered: why, as far as the capture shows
  // A diagnosis's case (diagnosis_of(code)): `frame` is its first frame,
  // `count` the frames that show it, `until` the time of the last; the
  // measured figure is the message.
  std::uint64_t count = 0;
  std::int64_t until = kNoTime;
  std::int8_t axis = -1;  // 0 yaw, 1 pitch, 2 roll; -1 none
};

// A decoded frame with its findings summarised.
struct DecodedEntry {
  const top::Frame* frame = nullptr;  // the parser's, valid during the event
  top::Decoded decoded;
  // Whether it may matter to a diagnosis (top/detail/prefilter.hpp).
  bool diagnosed = false;
  top::Severity worst = top::Severity::info;
  bool bad_checksum = false;
};

struct FrameEvent {
  FrameEvent() = default;
  // Where the frame is; the rest (reply, copy, notes) comes as the session
  // decides. (A constructor, not `FrameEvent{.n = ...}`, which g++ -O2
  // clears whole first: docs/perf/decisions.md, "FrameEvent by constructor".)
  FrameEvent(std::uint64_t n_, std::int64_t ts_, Position pos_, std::uint64_t stream_offset_,
             Transport transport_, const Conversation* conv_, const std::string* from_,
             const std::string* to_, const DecodedEntry* entry_) noexcept
      : n(n_),
        ts(ts_),
        pos(pos_),
        stream_offset(stream_offset_),
        transport(transport_),
        conv(conv_),
        from(from_),
        to(to_),
        entry(entry_) {}
  std::uint64_t n = 0;        // 1-based frame number
  std::int64_t ts = kNoTime;  // microseconds since the epoch
  Position pos;
  std::uint64_t stream_offset = 0;  // TCP/serial: offset in the direction's byte stream
  Transport transport{};
  const Conversation* conv = nullptr;
  const std::string* from = nullptr;  // endpoint text
  const std::string* to = nullptr;
  const DecodedEntry* entry = nullptr;
  std::uint64_t reply_to = 0;  // frame number of the request answered
  std::int64_t latency_us = -1;
  // A copy of frame `copy_of` the device sent to another port of the
  // client's host, or again (top::fan_out_copy_window_us): shown, counted
  // as a frame, but neither paired nor judged (0: not a copy).
  std::uint64_t copy_of = 0;
  std::vector<Note> notes;  // session findings on this frame
  top::Severity worst() const noexcept;
  std::uint64_t conv_id() const noexcept;
};

struct GarbageEvent {
  std::int64_t ts = kNoTime;
  Position pos;
  Transport transport{};
  const Conversation* conv = nullptr;
  const std::string* from = nullptr;
  const std::string* to = nullptr;
  const top::StreamItem* item = nullptr;
  std::uint64_t conv_id() const noexcept;
};

struct NoteEvent {
  std::int64_t ts = kNoTime;
  Position pos;
  Transport transport{};
  const Conversation* conv = nullptr;  // may be null (file-level)
  const std::string* from = nullptr;
  const std::string* to = nullptr;
  Note note;
  std::uint64_t conv_id() const noexcept;
};

class Sink {
 public:
  virtual ~Sink() = default;
  virtual void frame(const FrameEvent&) {}
  virtual void garbage(const GarbageEvent&) {}
  virtual void note(const NoteEvent&) {}
};

}  // namespace topdump
