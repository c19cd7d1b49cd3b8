// Writing captures for tests, sample captures and the bench generator:
// packets built byte by byte (Ethernet, VLAN, SLL, SLL2, BSD loopback, raw
// IP; IPv4/IPv6; UDP/TCP), pcap files written through libpcap
// (pcap_open_dead + pcap_dump_open) and pcapng files built by hand (libpcap
// cannot write several interfaces).
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

struct pcap;
struct pcap_dumper;

namespace topdump::pcapw {

using Ip4 = std::array<std::uint8_t, 4>;
using Ip6 = std::array<std::uint8_t, 16>;

std::string udp4(Ip4 src, Ip4 dst, std::uint16_t sport, std::uint16_t dport,
                 std::string_view payload);
std::string udp6(const Ip6& src, const Ip6& dst, std::uint16_t sport, std::uint16_t dport,
                 std::string_view payload);
inline constexpr std::uint8_t kSyn = 0x02, kAck = 0x10, kPsh = 0x08, kFin = 0x01;
std::string tcp4(Ip4 src, Ip4 dst, std::uint16_t sport, std::uint16_t dport, std::uint32_t seq,
                 std::uint32_t ack, std::uint8_t flags, std::string_view payload);
std::string tcp6(const Ip6& src, const Ip6& dst, std::uint16_t sport, std::uint16_t dport,
                 std::uint32_t seq, std::uint32_t ack, std::uint8_t flags,
                 std::string_view payload);

// Link layers around an IP packet (ethertype from the IP version).
std::string eth(std::string_view ip, std::vector<std::uint16_t> vlans = {});
std::string sll(std::string_view ip);
std::string sll2(std::string_view ip);
std::string null_lo(std::string_view ip);  // DLT_NULL, host (little-endian) AF
std::string loop_lo(std::string_view ip);  // DLT_LOOP, big-endian AF

// A pcap file written through libpcap.
class PcapWriter {
 public:
  PcapWriter(const std::string& path, int dlt, int snaplen = 65535);
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;
  bool ok() const { return dumper_ != nullptr; }
  // Writes a packet; caplen < bytes.size() cuts it (as a snap length would).
  void write(std::int64_t ts_us, std::string_view bytes, std::size_t caplen = SIZE_MAX);
  void close();

 private:
  pcap* p_ = nullptr;
  pcap_dumper* dumper_ = nullptr;
};

// A hand-built pcapng file (little-endian, microsecond timestamps).
struct NgPacket {
  std::uint32_t interface = 0;
  std::int64_t ts_us = 0;
  std::string bytes;
};
std::string pcapng(const std::vector<std::uint16_t>& linktypes,
                   const std::vector<NgPacket>& packets);

// The TOP checksum appended: frame("#TPUG2wGAA01") == "#TPUG2wGAA0136".
std::string frame(std::string_view without_checksum);

bool write_file(const std::string& path, std::string_view bytes);

}  // namespace topdump::pcapw
