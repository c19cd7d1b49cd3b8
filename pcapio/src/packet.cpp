#include "pcapio/packet.hpp"

namespace pcapio {

namespace {

void be16(std::string& s, std::size_t at, std::uint32_t v) {
  s[at] = static_cast<char>((v >> 8) & 0xFF);
  s[at + 1] = static_cast<char>(v & 0xFF);
}
void be32(std::string& s, std::size_t at, std::uint32_t v) {
  be16(s, at, v >> 16);
  be16(s, at + 2, v & 0xFFFF);
}

std::string ip4(Ip4 src, Ip4 dst, std::uint8_t proto, std::string_view l4, Ip4Options o) {
  std::string h(20, '\0');
  h[0] = 0x45;
  be16(h, 2, static_cast<std::uint32_t>(20 + l4.size()));
  be16(h, 4, o.id);
  if (o.dont_fragment) be16(h, 6, 0x4000);
  h[8] = 64;
  h[9] = static_cast<char>(proto);
  for (int i = 0; i < 4; ++i)
    h[12 + i] = static_cast<char>(src[i]), h[16 + i] = static_cast<char>(dst[i]);
  be16(h, 10, ip_checksum(h));
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

// UDP checksum 0: not computed (allowed for IPv4, and what topdump reads).
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

std::uint16_t ip_checksum(std::string_view bytes) noexcept {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i + 1 < bytes.size(); i += 2)
    sum += static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i]) << 8 |
                                      static_cast<std::uint8_t>(bytes[i + 1]));
  if (bytes.size() % 2)
    sum += static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes.back()) << 8);
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum & 0xFFFF);
}

std::string udp4(Ip4 s, Ip4 d, std::uint16_t sp, std::uint16_t dp, std::string_view p,
                 Ip4Options o) {
  return ip4(s, d, 17, udp(sp, dp, p), o);
}
std::string udp6(const Ip6& s, const Ip6& d, std::uint16_t sp, std::uint16_t dp,
                 std::string_view p) {
  return ip6(s, d, 17, udp(sp, dp, p));
}
std::string tcp4(Ip4 s, Ip4 d, std::uint16_t sp, std::uint16_t dp, std::uint32_t seq,
                 std::uint32_t ack, std::uint8_t flags, std::string_view p, Ip4Options o) {
  return ip4(s, d, 6, tcp(sp, dp, seq, ack, flags, p), o);
}
std::string tcp6(const Ip6& s, const Ip6& d, std::uint16_t sp, std::uint16_t dp, std::uint32_t seq,
                 std::uint32_t ack, std::uint8_t flags, std::string_view p) {
  return ip6(s, d, 6, tcp(sp, dp, seq, ack, flags, p));
}

std::string eth(std::string_view ip, std::vector<std::uint16_t> vlans, const Mac& dst,
                const Mac& src) {
  std::string e(12, '\0');
  for (std::size_t i = 0; i < 6; ++i)
    e[i] = static_cast<char>(dst[i]), e[6 + i] = static_cast<char>(src[i]);
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
  const std::uint32_t af = ethertype(ip) == 0x0800 ? 2 : 30;
  std::string h(4, '\0');
  for (std::size_t i = 0; i < 4; ++i) h[i] = static_cast<char>((af >> (8 * i)) & 0xFF);
  return h + std::string(ip);
}
std::string loop_lo(std::string_view ip) {
  std::string h(4, '\0');
  be32(h, 0, ethertype(ip) == 0x0800 ? 2 : 30);
  return h + std::string(ip);
}

}  // namespace pcapio
