// Target: topdump's TCP reassembly (Analyzer::segment). The input is a list
// of segments of one connection, each: flags byte (bit 0: direction, bit 1:
// SYN), a 32-bit sequence number given as a signed 16-bit delta from the
// direction's last one (so retransmissions, overlaps, gaps and reordering
// are all a few mutations away; bit 2 of flags makes it absolute instead),
// a length byte and that many payload bytes. Checks: nothing crashes, leaks
// or hangs, and the analyzer's bounded TCP buffers keep memory bounded
// (-rss_limit_mb).
#include <cstdint>
#include <string_view>

#include "check.hpp"
#include "session/analyzer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  size = topfuzz::capped(size);
  topdump::Sink sink;
  topdump::AnalyzerOptions opts;
  topdump::Analyzer a(opts, sink);
  topdump::Endpoint client, device;
  client.family = device.family = 4;
  client.addr[0] = 10;
  client.addr[3] = 1;
  device.addr[0] = 10;
  device.addr[3] = 2;
  client.port = 40000;
  device.port = 5000;
  std::uint32_t seq[2] = {1000, 900000};
  std::size_t at = 0;
  std::uint64_t record = 0;
  std::int64_t ts = 1'700'000'000'000'000;
  while (at + 4 <= size) {
    const std::uint8_t flags = data[at];
    const auto delta = static_cast<std::int16_t>(data[at + 1] << 8 | data[at + 2]);
    std::size_t len = data[at + 3];
    at += 4;
    if (len > size - at) len = size - at;
    const int dir = flags & 1;
    std::uint32_t s = (flags & 4) ? static_cast<std::uint32_t>(delta) * 65537u
                                  : seq[dir] + static_cast<std::uint32_t>(delta);
    const std::string_view payload(reinterpret_cast<const char*>(data + at), len);
    a.record(true);
    a.segment(ts, dir ? device : client, dir ? client : device, s, (flags & 2) != 0, payload,
              ++record, 54);
    seq[dir] = s + static_cast<std::uint32_t>(len);
    ts += 1000;
    at += len;
  }
  a.finish();
  return 0;
}
