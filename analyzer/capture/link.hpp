// Link dissection: a captured packet down to its UDP or TCP payload.
#pragma once

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
  CaptureSink& a_;
  std::set<std::string> tcp_top_;  // TCP flows recognised by content (bounded)
  Endpoint src_, dst_;             // the endpoints of the packet at hand
  // The UDP and TCP ports as tables: a lookup per packet.
  std::vector<bool> udp_port_ = std::vector<bool>(65536), tcp_port_ = std::vector<bool>(65536);
};

}  // namespace topdump
