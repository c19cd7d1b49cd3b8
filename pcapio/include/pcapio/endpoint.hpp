// One end of a conversation: an IPv4 or IPv6 address and a port, or a name
// (a serial line). topdump keys conversations by it; topsim and topconf
// record their traffic between two of them.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <string>

namespace pcapio {

struct Endpoint {
  std::uint8_t family = 0;  // 4, 6, or 0 for a named end
  std::array<std::uint8_t, 16> addr{};
  std::uint16_t port = 0;
  std::string name;  // family 0

  // An IPv4 end; `ip` in host order (0x7F000001 is 127.0.0.1).
  static Endpoint ipv4(std::uint32_t ip, std::uint16_t port);
  // The IPv4 address in host order (0 unless family 4).
  std::uint32_t ipv4() const noexcept;

  // Compared on every packet (topdump's conversation cache): ports and
  // family first, the address as two eight-byte words, the name last.
  bool operator==(const Endpoint& o) const noexcept {
    std::uint64_t a[2], b[2];
    std::memcpy(a, addr.data(), 16);
    std::memcpy(b, o.addr.data(), 16);
    return port == o.port && family == o.family && a[0] == b[0] && a[1] == b[1] && name == o.name;
  }
  // "10.0.0.1:5000", "[::1]:5000" (RFC 5952), or the name escaped
  // (top::escape).
  std::string text() const;
};

}  // namespace pcapio
