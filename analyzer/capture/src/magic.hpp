// The magic numbers of capture files (capture's own header).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

namespace topdump {

inline bool is_pcap_magic(std::string_view h) {
  if (h.size() < 4) return false;
  std::uint32_t m;
  std::memcpy(&m, h.data(), 4);
  return m == 0xa1b2c3d4 || m == 0xd4c3b2a1 || m == 0xa1b23c4d || m == 0x4d3cb2a1;
}

inline bool is_pcapng_magic(std::string_view h) {
  return h.size() >= 4 && h.compare(0, 4, "\x0a\x0d\x0d\x0a", 4) == 0;
}

// The first four bytes as hex ("a1b2c3d4").
inline std::string hex32(std::string_view b) {
  char t[9];
  std::snprintf(t, sizeof t, "%02x%02x%02x%02x", static_cast<unsigned char>(b[0]),
                static_cast<unsigned char>(b[1]), static_cast<unsigned char>(b[2]),
                static_cast<unsigned char>(b[3]));
  return t;
}

}  // namespace topdump
