// What capture hands on: timestamped payloads and byte chunks with their
// endpoints, records and source findings, to a CaptureSink. The session
// (session/analyzer.hpp) is the sink; capture knows nothing of it.
#pragma once

#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>

#include "findings/afindings.hpp"
#include "pcapio/endpoint.hpp"

namespace topdump {

// A time that is not known (a log line without one).
inline constexpr std::int64_t kNoTime = INT64_MIN;

enum class Transport : std::uint8_t { udp, tcp, serial };
inline std::string_view to_string(Transport t) noexcept {
  constexpr std::string_view kTransport[] = {"udp", "tcp", "serial"};
  static_assert(std::size(kTransport) == static_cast<std::size_t>(Transport::serial) + 1);
  const auto i = static_cast<std::size_t>(t);
  return i < std::size(kTransport) ? kTransport[i] : "?";
}

// One end of a conversation: an IP address and port, or a name (serial).
using Endpoint = pcapio::Endpoint;

// The receiver of everything a reader reads. Times are microseconds since
// the epoch (kNoTime: unknown); `record` is the 1-based packet, log chunk,
// line or CSV row, `offset` the byte offset in it. One call per record or
// payload, never per byte of a payload.
class CaptureSink {
 public:
  virtual ~CaptureSink() = default;
  // A record was read: TOP traffic or not (counts records).
  virtual void record(bool top_traffic) = 0;
  // A UDP payload (frames never span datagrams).
  virtual void datagram(std::int64_t ts, const Endpoint& src, const Endpoint& dst,
                        std::string_view payload, std::uint64_t record, std::uint32_t offset) = 0;
  // A TCP segment's payload with its sequence number (SYN: the segment
  // carries the SYN flag).
  virtual void segment(std::int64_t ts, const Endpoint& src, const Endpoint& dst, std::uint32_t seq,
                       bool syn, std::string_view payload, std::uint64_t record,
                       std::uint32_t offset) = 0;
  // Bytes of an in-order byte stream (a serial line, one direction).
  virtual void chunk(std::int64_t ts, Transport t, const Endpoint& src, const Endpoint& dst,
                     std::string_view bytes, std::uint64_t record, std::uint64_t offset) = 0;
  // A live line was quiet: bytes held to see whether CR/LF follows go on.
  virtual void flush_streams() {}
  // The serial recording holds both directions of the line by construction
  // (socat's relay log, two taps merged): a direction without a byte is a
  // silent device, not a line nobody recorded.
  virtual void both_ways() {}
  // A problem of the input itself (truncated file, bad packet, bad log line).
  virtual void source_note(std::int64_t ts, ACode code, std::string message, std::uint64_t record,
                           std::uint64_t offset) = 0;
  // True once the sink wants no more records (-c reached): readers may stop.
  bool done() const noexcept { return done_; }

 protected:
  bool done_ = false;
};

}  // namespace topdump
