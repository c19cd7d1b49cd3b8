// Packets built byte by byte: IPv4/IPv6 with UDP or TCP, and the link
// layers around them (Ethernet with VLAN tags, Linux SLL and SLL2, BSD
// loopback). One IPv4 header checksum for all.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pcapio {

using Ip4 = std::array<std::uint8_t, 4>;
using Ip6 = std::array<std::uint8_t, 16>;
using Mac = std::array<std::uint8_t, 6>;

// The Internet checksum (RFC 1071) of `bytes`: the ones' complement of the
// ones' complement sum of its 16-bit big-endian words.
std::uint16_t ip_checksum(std::string_view bytes) noexcept;

// What an IPv4 header carries besides addresses and protocol.
struct Ip4Options {
  std::uint16_t id = 0;
  bool dont_fragment = false;
};

std::string udp4(Ip4 src, Ip4 dst, std::uint16_t sport, std::uint16_t dport,
                 std::string_view payload, Ip4Options o = {});
std::string udp6(const Ip6& src, const Ip6& dst, std::uint16_t sport, std::uint16_t dport,
                 std::string_view payload);
inline constexpr std::uint8_t kSyn = 0x02, kAck = 0x10, kPsh = 0x08, kFin = 0x01;
std::string tcp4(Ip4 src, Ip4 dst, std::uint16_t sport, std::uint16_t dport, std::uint32_t seq,
                 std::uint32_t ack, std::uint8_t flags, std::string_view payload,
                 Ip4Options o = {});
std::string tcp6(const Ip6& src, const Ip6& dst, std::uint16_t sport, std::uint16_t dport,
                 std::uint32_t seq, std::uint32_t ack, std::uint8_t flags,
                 std::string_view payload);

// Link layers around an IP packet (ethertype from the IP version).
inline constexpr Mac kEthDst = {0x02, 0, 0, 0, 0, 0x02}, kEthSrc = {0x02, 0, 0, 0, 0, 0x01};
std::string eth(std::string_view ip, std::vector<std::uint16_t> vlans = {},
                const Mac& dst = kEthDst, const Mac& src = kEthSrc);
std::string sll(std::string_view ip);
std::string sll2(std::string_view ip);
std::string null_lo(std::string_view ip);  // DLT_NULL, host (little-endian) AF
std::string loop_lo(std::string_view ip);  // DLT_LOOP, big-endian AF

}  // namespace pcapio
