// Writes what topsim and topconf send and receive as a libpcap capture of
// Ethernet/IPv4/UDP (or TCP) packets with the real ports, so topdump and
// tcpdump decode it. Serial and pseudo-terminal traffic is recorded as UDP
// between 127.0.0.1 ports (documented in conformance/README.md).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

struct pcap;
struct pcap_dumper;

namespace topkit {

struct Endpoint {
  std::uint32_t ip = 0x7F000001;  // host order
  std::uint16_t port = 0;
};

class PcapWriter {
 public:
  // Opens `path` for writing; throws std::runtime_error naming the file.
  PcapWriter(const std::string& path, bool tcp);
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;

  // One packet from `from` to `to` carrying `payload`, stamped with the
  // wall clock. Payloads past 65000 bytes are cut in several packets.
  void write(const Endpoint& from, const Endpoint& to, std::string_view payload);
  void flush();
  std::uint64_t packets() const noexcept { return packets_; }

 private:
  void packet(const Endpoint& from, const Endpoint& to, std::string_view payload);
  pcap* pcap_ = nullptr;
  pcap_dumper* dumper_ = nullptr;
  bool tcp_ = false;
  std::uint32_t seq_a_ = 1000, seq_b_ = 50000;  // per direction (lower port first)
  std::uint16_t ip_id_ = 1;
  std::uint64_t packets_ = 0;
};

}  // namespace topkit
