// TCP reassembly of one direction of a connection: segments in capture
// order in, the byte stream in sequence order out. Retransmissions and
// overlaps are delivered once (the first copy wins, and a copy that differs
// is reported), segments ahead of the stream are held until the bytes
// before them arrive, and bytes never captured become a gap after which the
// stream restarts. Memory is bounded: past the limits the held bytes are
// dropped as a gap.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "findings/afindings.hpp"

namespace topdump {

inline constexpr std::size_t kMaxTcpHeld = 1u << 20;  // out-of-order bytes per direction
inline constexpr std::size_t kMaxTcpSegments = 1024;  // out-of-order segments per direction

// Where reassembly hands what it finds. `record` and `offset` say where
// the segment concerned sits in the capture.
class TcpOutput {
 public:
  virtual ~TcpOutput() = default;
  // The next bytes of the stream, from the segment of `record` (`offset`:
  // the bytes' offset in the record).
  virtual void bytes(std::string_view b, std::uint64_t record, std::uint64_t offset,
                     std::int64_t ts) = 0;
  // A finding: tcp-retransmission, tcp-overlap-differs, tcp-out-of-order,
  // reassembly-limit or tcp-gap.
  virtual void finding(ACode code, std::string message, std::uint64_t record, std::uint64_t offset,
                       std::int64_t ts) = 0;
  // `skipped` bytes were never captured: the stream restarts after them
  // (reported first as a tcp-gap finding).
  virtual void gap(std::uint64_t skipped, std::int64_t ts) = 0;
};

class TcpReassembly {
 public:
  explicit TcpReassembly(std::size_t max_held = kMaxTcpHeld) : max_held_(max_held) {}

  // A segment at sequence number `seq` (`syn`: it carries SYN, which takes
  // one sequence number) whose payload sits at `offset` of `record`.
  void segment(std::uint32_t seq, bool syn, std::string_view payload, std::uint64_t record,
               std::uint32_t offset, std::int64_t ts, TcpOutput& out);
  // The end of the stream: each held segment is delivered after the gap
  // before it.
  void finish(std::int64_t ts, TcpOutput& out);

  // The stream offset of the next byte: bytes delivered and skipped so far.
  std::uint64_t stream_offset() const noexcept { return stream_off_; }
  // Bytes and segments held ahead of the stream.
  std::size_t held_bytes() const noexcept { return held_; }
  std::size_t held_segments() const noexcept { return ooo_.size(); }

 private:
  // A segment held until the bytes before it arrive.
  struct Held {
    std::string bytes;
    std::uint64_t record;
    std::uint32_t offset;
    std::int64_t ts;
  };
  bool place(std::uint32_t seq, std::string_view p, std::uint64_t record, std::uint64_t offset,
             std::int64_t ts, TcpOutput& out);
  void overlap_check(std::uint32_t seq, std::string_view bytes, std::uint64_t record,
                     std::uint64_t offset, std::int64_t ts, TcpOutput& out);
  void deliver(std::string_view bytes, std::uint64_t record, std::uint64_t offset, std::int64_t ts,
               TcpOutput& out);
  void drain(TcpOutput& out);
  void hold(std::uint32_t seq, std::string_view payload, std::uint64_t record, std::uint32_t offset,
            std::int64_t ts, TcpOutput& out);
  void gap(std::int64_t ts, TcpOutput& out);
  std::map<std::uint32_t, Held>::iterator closest();

  std::size_t max_held_;
  bool init_ = false;
  std::uint32_t next_seq_ = 0;
  std::uint64_t stream_off_ = 0;  // bytes delivered and skipped
  std::uint64_t fed_ = 0;         // bytes delivered since the stream (re)started
  std::map<std::uint32_t, Held> ooo_;
  std::size_t held_ = 0;
  std::string tail_;  // the last bytes delivered, for overlap checks
};

}  // namespace topdump
