#include "pcapio/endpoint.hpp"

#include <cstdio>

#include "top/text.hpp"

namespace pcapio {

Endpoint Endpoint::ipv4(std::uint32_t ip, std::uint16_t port) {
  Endpoint e;
  e.family = 4;
  for (int i = 0; i < 4; ++i)
    e.addr[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(ip >> (24 - 8 * i));
  e.port = port;
  return e;
}

std::uint32_t Endpoint::ipv4() const noexcept {
  if (family != 4) return 0;
  return std::uint32_t{addr[0]} << 24 | std::uint32_t{addr[1]} << 16 | std::uint32_t{addr[2]} << 8 |
         addr[3];
}

std::string Endpoint::text() const {
  char b[64];
  if (family == 4) {
    std::snprintf(b, sizeof b, "%u.%u.%u.%u:%u", addr[0], addr[1], addr[2], addr[3], port);
    return b;
  }
  if (family == 6) {
    // RFC 5952 style: longest run of zero groups as "::".
    std::uint16_t g[8];
    for (int i = 0; i < 8; ++i)
      g[i] = static_cast<std::uint16_t>(addr[2 * i] << 8 | addr[2 * i + 1]);
    int best = -1, best_len = 0;
    for (int i = 0; i < 8;) {
      if (g[i] != 0) {
        ++i;
        continue;
      }
      int j = i;
      while (j < 8 && g[j] == 0) ++j;
      if (j - i > best_len && j - i >= 2) best = i, best_len = j - i;
      i = j;
    }
    std::string s = "[";
    for (int i = 0; i < 8; ++i) {
      if (i == best) {
        s += "::";
        i += best_len - 1;
        continue;
      }
      if (!s.empty() && s.back() != ':' && s.back() != '[') s += ':';
      std::snprintf(b, sizeof b, "%x", g[i]);
      s += b;
    }
    s += "]:" + std::to_string(port);
    return s;
  }
  return top::escape(name);
}

}  // namespace pcapio
