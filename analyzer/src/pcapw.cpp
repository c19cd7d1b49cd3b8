#include "pcapw.hpp"

#include <pcap/pcap.h>

#include <fstream>

#include "top/frame.hpp"

namespace topdump::pcapw {

namespace {
void be16(std::string& s, std::size_t at, std::uint32_t v) {
  s[at] = static_cast<char>((v >> 8) & 0xFF);
  s[at + 1] = static_cast<char>(v & 0xFF);
}
void be32(std::string& s, std::size_t at, std::uint32_t v) {
  be16(s, at, v >> 16);
  be16(s, at + 2, v & 0xFFFF);
}
void le16a(std::string& s, std::uint32_t v) {
  s += static_cast<char>(v & 0xFF);
  s += static_cast<char>((v >> 8) & 0xFF);
}
void le32a(std::string& s, std::uint32_t v) {
  le16a(s, v & 0xFFFF);
  le16a(s, v >> 16);
}
std::string ip4(Ip4 src, Ip4 dst, std::uint8_t proto, std::string_view l4) {
  std::string h(20, '\0');
  h[0] = 0x45;
  be16(h, 2, static_cast<std::uint32_t>(20 + l4.size()));
  h[8] = 64;
  h[9] = static_cast<char>(proto);
  for (int i = 0; i < 4; ++i)
    h[12 + i] = static_cast<char>(src[i]), h[16 + i] = static_cast<char>(dst[i]);
  std::uint32_t sum = 0;
  for (int i = 0; i < 20; i += 2)
    sum += static_cast<std::uint32_t>(static_cast<std::uint8_t>(h[i]) << 8 |
                                      static_cast<std::uint8_t>(h[i + 1]));
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  be16(h, 10, ~sum & 0xFFFF);
  return h + std::string(l4);
}
std::string ip6(const Ip6& src, const Ip6& dst, std::uint8_t proto, std::string_view l4) {
  std::string h(40, '\0');
  h[0] = 0x60;
  be16(h, 4, static_cast<std::uint32_t>(l4.size()));
  h[6] = static_cast<char>(proto);
  h[7] = 64;
  for (int i = 0; i < 16; ++i)
    h[8 + i] = static_cast<char>(src[i]), h[24 + i] = static_cast<char>(dst[i]);
  return h + std::string(l4);
}
std::string udp(std::uint16_t sport, std::uint16_t dport, std::string_view payload) {
  std::string u(8, '\0');
  be16(u, 0, sport);
  be16(u, 2, dport);
  be16(u, 4, static_cast<std::uint32_t>(8 + payload.size()));
  return u + std::string(payload);
}
std::string tcp(std::uint16_t sport, std::uint16_t dport, std::uint32_t seq, std::uint32_t ack,
                std::uint8_t flags, std::string_view payload) {
  std::string t(20, '\0');
  be16(t, 0, sport);
  be16(t, 2, dport);
  be32(t, 4, seq);
  be32(t, 8, ack);
  t[12] = 0x50;
  t[13] = static_cast<char>(flags);
  be16(t, 14, 65535);
  return t + std::string(payload);
}
std::uint16_t ethertype(std::string_view ip) {
  return !ip.empty() && (static_cast<std::uint8_t>(ip[0]) >> 4) == 6 ? 0x86DD : 0x0800;
}
}  // namespace

std::string udp4(Ip4 s, Ip4 d, std::uint16_t sp, std::uint16_t dp, std::string_view p) {
  return ip4(s, d, 17, udp(sp, dp, p));
}
std::string udp6(const Ip6& s, const Ip6& d, std::uint16_t sp, std::uint16_t dp,
                 std::string_view p) {
  return ip6(s, d, 17, udp(sp, dp, p));
}
std::string tcp4(Ip4 s, Ip4 d, std::uint16_t sp, std::uint16_t dp, std::uint32_t seq,
                 std::uint32_t ack, std::uint8_t flags, std::string_view p) {
  return ip4(s, d, 6, tcp(sp, dp, seq, ack, flags, p));
}
std::string tcp6(const Ip6& s, const Ip6& d, std::uint16_t sp, std::uint16_t dp, std::uint32_t seq,
                 std::uint32_t ack, std::uint8_t flags, std::string_view p) {
  return ip6(s, d, 6, tcp(sp, dp, seq, ack, flags, p));
}

std::string eth(std::string_view ip, std::vector<std::uint16_t> vlans) {
  std::string e = std::string("\x02\x00\x00\x00\x00\x02\x02\x00\x00\x00\x00\x01", 12);
  for (std::uint16_t v : vlans) {
    std::string t(4, '\0');
    be16(t, 0, 0x8100);
    be16(t, 2, v);
    e += t;
  }
  std::string t(2, '\0');
  be16(t, 0, ethertype(ip));
  return e + t + std::string(ip);
}
std::string sll(std::string_view ip) {
  std::string h(16, '\0');
  be16(h, 0, 0);  // packet for us
  be16(h, 2, 1);  // ARPHRD_ETHER
  be16(h, 4, 6);
  for (int i = 0; i < 6; ++i) h[6 + i] = static_cast<char>(0x10 + i);
  be16(h, 14, ethertype(ip));
  return h + std::string(ip);
}
std::string sll2(std::string_view ip) {
  std::string h(20, '\0');
  be16(h, 0, ethertype(ip));
  be32(h, 4, 2);  // interface index
  be16(h, 8, 1);  // ARPHRD_ETHER
  h[10] = 0;      // packet type
  h[11] = 6;
  for (int i = 0; i < 6; ++i) h[12 + i] = static_cast<char>(0x20 + i);
  return h + std::string(ip);
}
std::string null_lo(std::string_view ip) {
  std::string h;
  le32a(h, ethertype(ip) == 0x0800 ? 2 : 30);
  return h + std::string(ip);
}
std::string loop_lo(std::string_view ip) {
  std::string h(4, '\0');
  be32(h, 0, ethertype(ip) == 0x0800 ? 2 : 30);
  return h + std::string(ip);
}

PcapWriter::PcapWriter(const std::string& path, int dlt, int snaplen) {
  p_ = pcap_open_dead_with_tstamp_precision(dlt, snaplen, PCAP_TSTAMP_PRECISION_MICRO);
  if (p_) dumper_ = pcap_dump_open(p_, path.c_str());
}
PcapWriter::~PcapWriter() { close(); }
void PcapWriter::close() {
  if (dumper_) pcap_dump_close(dumper_);
  if (p_) pcap_close(p_);
  dumper_ = nullptr;
  p_ = nullptr;
}
void PcapWriter::write(std::int64_t ts, std::string_view bytes, std::size_t caplen) {
  if (!dumper_) return;
  pcap_pkthdr h{};
  h.ts.tv_sec = static_cast<time_t>(ts / 1000000);
  h.ts.tv_usec = static_cast<suseconds_t>(ts % 1000000);
  h.len = static_cast<bpf_u_int32>(bytes.size());
  h.caplen = static_cast<bpf_u_int32>(std::min(caplen, bytes.size()));
  pcap_dump(reinterpret_cast<u_char*>(dumper_), &h, reinterpret_cast<const u_char*>(bytes.data()));
}

std::string pcapng(const std::vector<std::uint16_t>& linktypes,
                   const std::vector<NgPacket>& packets) {
  std::string out;
  auto block = [&](std::uint32_t type, const std::string& body) {
    std::string b;
    std::uint32_t len = static_cast<std::uint32_t>(12 + body.size());
    le32a(b, type);
    le32a(b, len);
    b += body;
    le32a(b, len);
    out += b;
  };
  std::string shb;
  le32a(shb, 0x1A2B3C4D);
  le16a(shb, 1);
  le16a(shb, 0);
  le32a(shb, 0xFFFFFFFF);
  le32a(shb, 0xFFFFFFFF);
  block(0x0A0D0D0A, shb);
  for (std::uint16_t lt : linktypes) {
    std::string idb;
    le16a(idb, lt);
    le16a(idb, 0);
    le32a(idb, 65535);
    block(1, idb);
  }
  for (const NgPacket& p : packets) {
    std::string epb;
    le32a(epb, p.interface);
    auto ts = static_cast<std::uint64_t>(p.ts_us);
    le32a(epb, static_cast<std::uint32_t>(ts >> 32));
    le32a(epb, static_cast<std::uint32_t>(ts & 0xFFFFFFFF));
    le32a(epb, static_cast<std::uint32_t>(p.bytes.size()));
    le32a(epb, static_cast<std::uint32_t>(p.bytes.size()));
    epb += p.bytes;
    while (epb.size() % 4) epb += '\0';
    block(6, epb);
  }
  return out;
}

std::string frame(std::string_view s) {
  char c[2];
  top::put_hex2(top::checksum(s), c);
  return std::string(s) + std::string(c, 2);
}

bool write_file(const std::string& path, std::string_view bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(f);
}

}  // namespace topdump::pcapw
