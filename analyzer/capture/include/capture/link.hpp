// Link dissection: a captured packet down to its UDP or TCP payload.
#pragma once

#include <array>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "capture/sink.hpp"

namespace topdump {

// The header values dissection tells apart.
inline constexpr std::uint16_t kEtherTypeIpv4 = 0x0800;
inline constexpr std::uint16_t kEtherTypeIpv6 = 0x86DD;
inline constexpr std::uint16_t kEtherTypeVlan = 0x8100;     // 802.1Q
inline constexpr std::uint16_t kEtherTypeQinQ = 0x88A8;     // 802.1ad
inline constexpr std::uint16_t kEtherTypeQinQOld = 0x9100;  // pre-standard 802.1ad
inline constexpr std::uint8_t kIpProtoUdp = 17;
inline constexpr std::uint8_t kIpProtoTcp = 6;

// How many TCP flows on unknown ports, recognised by their content, are
// remembered (as many as the session's conversations).
inline constexpr std::size_t kMaxContentFlows = 4096;

// True when a payload on an unknown port carries something that starts like
// a TOP frame ("#tp", "#TP", "#tP", "#Tp", "#PDP16TMP").
bool looks_like_top(std::string_view payload) noexcept;

// Dissects one captured packet of link type `dlt` (Ethernet with VLAN tags,
// Linux SLL/SLL2, raw IP, BSD loopback; IPv4/IPv6; UDP/TCP) and hands any
// TOP payload to the sink: a datagram or segment on one of the ports, or
// one whose payload looks like TOP. Returns false when it is not TOP traffic.
class Dissector {
 public:
  Dissector(CaptureSink& a, const std::set<std::uint16_t>& udp_ports,
            const std::set<std::uint16_t>& tcp_ports)
      : a_(a) {
    for (auto p : udp_ports) udp_port_[p] = true;
    for (auto p : tcp_ports) tcp_port_[p] = true;
  }
  bool packet(int dlt, std::int64_t ts, const std::uint8_t* data, std::uint32_t caplen,
              std::uint32_t len, std::uint64_t record);
  static bool supported(int dlt);

 private:
  bool ip(std::int64_t ts, const std::uint8_t* p, std::size_t n, std::size_t off,
          std::uint64_t record);
  void bad(std::int64_t ts, std::uint64_t record, std::size_t off, std::string msg);
  // Whether the IPv4 UDP datagram at hand (identification `id`, not 0) is
  // one the capture already recorded: a bridged or mirrored link, or two
  // interfaces, give a packet twice, the same in every byte, and the copy
  // would be a second request or an unsolicited reply. A sender gives each
  // datagram its own identification (one that sets none, 0, is not judged),
  // so the same identification, addresses, ports and payload within
  // kDuplicateUs is the same packet.
  bool duplicate(std::int64_t ts, std::uint16_t id, std::string_view payload) noexcept;
  static constexpr std::int64_t kDuplicateUs = 1'000'000;
  // The last datagram seen with each low byte of identification: its
  // time, identification, ends, size, and first and last eight bytes.
  struct Seen {
    std::int64_t ts = kNoTime;
    std::uint64_t head = 0, tail = 0;
    std::uint32_t saddr = 0, daddr = 0, ports = 0, len = 0;
    std::uint16_t id = 0;
  };
  std::array<Seen, 256> seen_{};
  std::int64_t dup_gap_us_ = 0;  // the last duplicate's distance from its original
  CaptureSink& a_;
  std::set<std::string> tcp_top_;  // TCP flows recognised by content (bounded)
  Endpoint src_, dst_;             // the endpoints of the packet at hand
  // The UDP and TCP ports as tables: a lookup per packet.
  std::vector<bool> udp_port_ = std::vector<bool>(65536), tcp_port_ = std::vector<bool>(65536);
};

}  // namespace topdump
