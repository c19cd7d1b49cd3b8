#include "common/pcap_writer.hpp"

#include <pcap/pcap.h>
#include <sys/time.h>

#include <algorithm>
#include <cstring>
#include <vector>

namespace topkit {
namespace {

void put16(std::vector<unsigned char>& b, std::size_t at, std::uint32_t v) {
  b[at] = static_cast<unsigned char>((v >> 8) & 0xFF);
  b[at + 1] = static_cast<unsigned char>(v & 0xFF);
}
void put32(std::vector<unsigned char>& b, std::size_t at, std::uint32_t v) {
  put16(b, at, v >> 16);
  put16(b, at + 2, v & 0xFFFF);
}

std::uint16_t ip_checksum(const unsigned char* p, std::size_t n) {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i + 1 < n; i += 2)
    sum += static_cast<std::uint32_t>(p[i] << 8 | p[i + 1]);
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum & 0xFFFF);
}

}  // namespace

PcapWriter::PcapWriter(const std::string& path, bool tcp) : tcp_(tcp) {
  pcap_ = pcap_open_dead(DLT_EN10MB, 65535);
  if (!pcap_) throw std::runtime_error(path + ": pcap_open_dead failed");
  dumper_ = pcap_dump_open(pcap_, path.c_str());
  if (!dumper_) {
    std::string err = path + ": " + pcap_geterr(pcap_);
    pcap_close(pcap_);
    pcap_ = nullptr;
    throw std::runtime_error(err);
  }
}

PcapWriter::~PcapWriter() {
  if (dumper_) pcap_dump_close(dumper_);
  if (pcap_) pcap_close(pcap_);
}

void PcapWriter::flush() {
  if (dumper_) pcap_dump_flush(dumper_);
}

void PcapWriter::write(const Endpoint& from, const Endpoint& to, std::string_view payload) {
  constexpr std::size_t kMax = 65000;
  do {
    const std::string_view part = payload.substr(0, std::min(kMax, payload.size()));
    packet(from, to, part);
    payload.remove_prefix(part.size());
  } while (!payload.empty());
}

void PcapWriter::packet(const Endpoint& from, const Endpoint& to, std::string_view payload) {
  const std::size_t l4 = tcp_ ? 20 : 8;
  std::vector<unsigned char> b(14 + 20 + l4 + payload.size(), 0);
  // Ethernet: locally administered MACs derived from the ports.
  const unsigned char dst_mac[6] = {0x02,
                                    0,
                                    0,
                                    0,
                                    static_cast<unsigned char>(to.port >> 8),
                                    static_cast<unsigned char>(to.port & 0xFF)};
  const unsigned char src_mac[6] = {0x02,
                                    0,
                                    0,
                                    0,
                                    static_cast<unsigned char>(from.port >> 8),
                                    static_cast<unsigned char>(from.port & 0xFF)};
  std::memcpy(&b[0], dst_mac, 6);
  std::memcpy(&b[6], src_mac, 6);
  put16(b, 12, 0x0800);
  // IPv4
  const std::size_t ip = 14;
  b[ip] = 0x45;
  put16(b, ip + 2, static_cast<std::uint32_t>(20 + l4 + payload.size()));
  put16(b, ip + 4, ip_id_++);
  put16(b, ip + 6, 0x4000);  // DF
  b[ip + 8] = 64;
  b[ip + 9] = tcp_ ? 6 : 17;
  put32(b, ip + 12, from.ip);
  put32(b, ip + 16, to.ip);
  put16(b, ip + 10, ip_checksum(&b[ip], 20));
  const std::size_t t = ip + 20;
  put16(b, t, from.port);
  put16(b, t + 2, to.port);
  if (tcp_) {
    const bool a_side = from.port < to.port;
    std::uint32_t& seq = a_side ? seq_a_ : seq_b_;
    std::uint32_t& ack = a_side ? seq_b_ : seq_a_;
    put32(b, t + 4, seq);
    put32(b, t + 8, ack);
    b[t + 12] = 0x50;
    b[t + 13] = 0x18;  // PSH ACK
    put16(b, t + 14, 65535);
    seq += static_cast<std::uint32_t>(payload.size());
  } else {
    put16(b, t + 4, static_cast<std::uint32_t>(8 + payload.size()));
    // UDP checksum 0: not computed (allowed for IPv4).
  }
  std::memcpy(b.data() + t + l4, payload.data(), payload.size());
  pcap_pkthdr h{};
  gettimeofday(&h.ts, nullptr);
  h.caplen = static_cast<bpf_u_int32>(b.size());
  h.len = h.caplen;
  pcap_dump(reinterpret_cast<u_char*>(dumper_), &h, b.data());
  ++packets_;
}

}  // namespace topkit
