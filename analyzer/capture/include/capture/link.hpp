// Link dissection: a captured packet down to its UDP or TCP payload.
#pragma once

#include <algorithm>
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

// A set of ports, looked up for each packet: a 64-bit filter on a port's
// low six bits, then the few ports themselves (topdump's own are 6). Two
// 65536-entry tables cost every capture read 16 KB zeroed and two heap
// blocks, which the fuzz targets paid per input (docs/perf/fuzz-speed.md,
// "Issue 48: the per-conversation cost").
class PortTable {
 public:
  explicit PortTable(const std::set<std::uint16_t>& ports) {
    if (ports.size() <= few_.size()) {
      for (auto p : ports) few_[n_++] = p;
    } else {
      many_.assign(ports.begin(), ports.end());  // sorted, as the set is
    }
    for (auto p : ports) filter_ |= bit(p);
  }
  bool operator[](std::uint16_t p) const noexcept {
    if (!(filter_ & bit(p))) return false;
    for (std::size_t i = 0; i < n_; ++i)
      if (few_[i] == p) return true;
    return std::binary_search(many_.begin(), many_.end(), p);
  }

 private:
  static std::uint64_t bit(std::uint16_t p) noexcept { return std::uint64_t{1} << (p & 63); }
  std::uint64_t filter_ = 0;
  std::array<std::uint16_t, 8> few_{};
  std::size_t n_ = 0;
  std::vector<std::uint16_t> many_;  // more than few_ holds: all of them
};

// Dissects one captured packet of link type `dlt` (Ethernet with VLAN tags,
// Linux SLL/SLL2, raw IP, BSD loopback; IPv4/IPv6; UDP/TCP) and hands any
// TOP payload to the sink: a datagram or segment on one of the ports, or
// one whose payload looks like TOP. Returns false when it is not TOP traffic.
class Dissector {
 public:
  Dissector(CaptureSink& a, const std::set<std::uint16_t>& udp_ports,
            const std::set<std::uint16_t>& tcp_ports)
      : a_(a), udp_port_(udp_ports), tcp_port_(tcp_ports) {}
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
  // time, identification, ends, size, and first and last eight bytes. A
  // slot is read only once `seen_used_` has its bit: the 10 KB are not
  // zeroed for each capture read (docs/perf/fuzz-speed.md, "Issue 48: the
  // per-conversation cost").
  struct Seen {
    std::int64_t ts;
    std::uint64_t head, tail;
    std::uint32_t saddr, daddr, ports, len;
    std::uint16_t id;
  };
  std::array<Seen, 256> seen_;
  std::array<std::uint64_t, 4> seen_used_{};
  std::int64_t dup_gap_us_ = 0;  // the last duplicate's distance from its original
  CaptureSink& a_;
  std::set<std::string> tcp_top_;  // TCP flows recognised by content (bounded)
  Endpoint src_, dst_;             // the endpoints of the packet at hand
  PortTable udp_port_, tcp_port_;  // the UDP and TCP ports
};

}  // namespace topdump
