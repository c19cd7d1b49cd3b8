// Link dissection: a captured packet's link, IP and UDP/TCP headers, and
// the TOP payload it carries handed to the sink.
#include "capture/link.hpp"

#include <pcap/pcap.h>

#include <algorithm>
#include <cstring>

namespace topdump {

bool looks_like_top(std::string_view p) noexcept {
  for (std::size_t i = p.find('#'); i != std::string_view::npos; i = p.find('#', i + 1)) {
    if (i + 2 < p.size() && (p[i + 1] == 'T' || p[i + 1] == 't') &&
        (p[i + 2] == 'P' || p[i + 2] == 'p'))
      return true;
    if (p.substr(i, 9) == "#PDP16TMP") return true;
  }
  return false;
}

namespace {
constexpr int kDltLoop = 108;
constexpr int kDltRaw1 = 12;
constexpr int kDltRaw2 = 14;
constexpr int kDltSll = 113;
constexpr int kDltSll2 = 276;
constexpr int kDltIpv4 = 228;
constexpr int kDltIpv6 = 229;

// IPv6 extension headers dissection skips (and the fragment header, which
// it does not reassemble).
constexpr std::uint8_t kIpv6HopByHop = 0;
constexpr std::uint8_t kIpv6Routing = 43;
constexpr std::uint8_t kIpv6Fragment = 44;
constexpr std::uint8_t kIpv6DestOptions = 60;

std::uint16_t be16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] << 8 | p[1]); }
std::uint32_t be32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}
}  // namespace

bool Dissector::supported(int dlt) {
  switch (dlt) {
    case DLT_NULL:
    case kDltLoop:
    case DLT_EN10MB:
    case kDltRaw1:
    case kDltRaw2:
    case kDltSll:
    case kDltSll2:
    case kDltIpv4:
    case kDltIpv6:
      return true;
  }
  return false;
}

void Dissector::bad(std::int64_t ts, std::uint64_t record, std::size_t off, std::string msg) {
  a_.source_note(ts, ACode::bad_packet, std::move(msg), record, off);
}

bool Dissector::duplicate(std::int64_t ts, std::uint16_t id, std::string_view payload) noexcept {
  Seen now{};
  now.ts = ts;
  now.id = id;
  now.len = static_cast<std::uint32_t>(payload.size());
  std::memcpy(&now.saddr, src_.addr.data(), 4);
  std::memcpy(&now.daddr, dst_.addr.data(), 4);
  now.ports = std::uint32_t{src_.port} << 16 | dst_.port;
  // the first and last eight bytes (a TOP datagram has at least ten)
  const std::size_t k = std::min<std::size_t>(payload.size(), 8);
  std::memcpy(&now.head, payload.data(), k);
  std::memcpy(&now.tail, payload.data() + payload.size() - k, k);
  Seen& s = seen_[id & 0xFF];
  std::uint64_t& used = seen_used_[(id & 0xFF) >> 6];
  const std::uint64_t bit = std::uint64_t{1} << (id & 63);
  const bool same = (used & bit) && s.ts != kNoTime && ts != kNoTime && ts >= s.ts &&
                    ts - s.ts <= kDuplicateUs && s.id == id && s.saddr == now.saddr &&
                    s.daddr == now.daddr && s.ports == now.ports && s.len == now.len &&
                    s.head == now.head && s.tail == now.tail;
  if (same) {
    dup_gap_us_ = ts - s.ts;
    return true;  // the original stays the one remembered
  }
  s = now;
  used |= bit;
  return false;
}

bool Dissector::packet(int dlt, std::int64_t ts, const std::uint8_t* p, std::uint32_t caplen,
                       std::uint32_t len, std::uint64_t record) {
  if (caplen < len)
    a_.source_note(ts, ACode::snaplen_cut,
                   "packet cut by the snap length: " + std::to_string(caplen) + " of " +
                       std::to_string(len) + " bytes captured",
                   record, caplen);
  std::size_t n = caplen, off = 0;
  std::uint16_t ethertype = 0;
  switch (dlt) {
    case DLT_NULL:
    case kDltLoop: {
      if (n < 4) return bad(ts, record, 0, "loopback header cut short"), false;
      std::uint32_t af = dlt == kDltLoop ? be32(p)
                                         : (std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 |
                                            std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24);
      if (dlt == DLT_NULL && af > 0xFFFF) af = be32(p);  // written on a big-endian host
      off = 4;
      if (af == 2)
        ethertype = kEtherTypeIpv4;
      else if (af == 10 || af == 24 || af == 28 || af == 30)
        ethertype = kEtherTypeIpv6;
      else
        return false;
      break;
    }
    case DLT_EN10MB: {
      if (n < 14) return bad(ts, record, 0, "Ethernet header cut short"), false;
      ethertype = be16(p + 12);
      off = 14;
      while (ethertype == kEtherTypeVlan || ethertype == kEtherTypeQinQ ||
             ethertype == kEtherTypeQinQOld) {
        if (n < off + 4) return bad(ts, record, off, "VLAN tag cut short"), false;
        ethertype = be16(p + off + 2);
        off += 4;
      }
      break;
    }
    case kDltSll:
      if (n < 16) return bad(ts, record, 0, "SLL header cut short"), false;
      ethertype = be16(p + 14);
      off = 16;
      break;
    case kDltSll2:
      if (n < 20) return bad(ts, record, 0, "SLL2 header cut short"), false;
      ethertype = be16(p);
      off = 20;
      break;
    case kDltRaw1:
    case kDltRaw2:
    case kDltIpv4:
    case kDltIpv6:
      if (n < 1) return false;
      ethertype = (p[0] >> 4) == 6 ? kEtherTypeIpv6 : kEtherTypeIpv4;
      break;
    default:
      return false;
  }
  if (ethertype != kEtherTypeIpv4 && ethertype != kEtherTypeIpv6) return false;
  return ip(ts, p, n, off, record);
}

bool Dissector::ip(std::int64_t ts, const std::uint8_t* p, std::size_t n, std::size_t off,
                   std::uint64_t record) {
  // Reused from packet to packet (name stays empty): the stores below are
  // all that change.
  Endpoint& src = src_;
  Endpoint& dst = dst_;
  std::uint8_t proto = 0;
  std::uint16_t ip_id = 0;  // IPv4's identification (0: none, or IPv6)
  std::size_t l4 = 0, end = n;
  if (n <= off) return bad(ts, record, off, "IP header missing"), false;
  unsigned version = p[off] >> 4;
  if (version == 4) {
    if (n < off + 20) return bad(ts, record, off, "IPv4 header cut short"), false;
    std::size_t ihl = (p[off] & 0x0F) * 4u;
    if (ihl < 20 || n < off + ihl) return bad(ts, record, off, "bad IPv4 header length"), false;
    std::size_t total = be16(p + off + 2);
    if (total < ihl)
      return bad(ts, record, off + 2, "IPv4 total length below header length"), false;
    end = std::min(n, off + total);
    ip_id = be16(p + off + 4);
    std::uint16_t frag = be16(p + off + 6);
    proto = p[off + 9];
    if ((frag & 0x3FFF) != 0 && (proto == kIpProtoUdp || proto == kIpProtoTcp))
      return bad(ts, record, off + 6, "IPv4 fragment (not reassembled)"), false;
    src.family = dst.family = 4;
    // Each address in one sixteen-byte store: the conversation lookup reads
    // it right after in eight-byte words, and a load that spans several
    // smaller stores waits for them to retire.
    std::uint64_t s4[2] = {0, 0}, d4[2] = {0, 0};
    std::memcpy(s4, p + off + 12, 4);
    std::memcpy(d4, p + off + 16, 4);
    std::memcpy(src.addr.data(), s4, 16);
    std::memcpy(dst.addr.data(), d4, 16);
    l4 = off + ihl;
  } else if (version == 6) {
    if (n < off + 40) return bad(ts, record, off, "IPv6 header cut short"), false;
    end = std::min(n, off + 40 + be16(p + off + 4));
    proto = p[off + 6];
    src.family = dst.family = 6;
    std::memcpy(src.addr.data(), p + off + 8, 16);
    std::memcpy(dst.addr.data(), p + off + 24, 16);
    l4 = off + 40;
    for (int hops = 0; hops < 8 && (proto == kIpv6HopByHop || proto == kIpv6Routing ||
                                    proto == kIpv6DestOptions || proto == kIpv6Fragment);
         ++hops) {
      if (end < l4 + 8) return bad(ts, record, l4, "IPv6 extension header cut short"), false;
      if (proto == kIpv6Fragment)
        return bad(ts, record, l4, "IPv6 fragment (not reassembled)"), false;
      std::uint8_t next = p[l4];
      l4 += (p[l4 + 1] + 1u) * 8u;
      proto = next;
    }
  } else {
    return bad(ts, record, off, "IP version " + std::to_string(version)), false;
  }
  if (proto == kIpProtoUdp) {
    if (end < l4 + 8) return bad(ts, record, l4, "UDP header cut short"), false;
    src.port = be16(p + l4);
    dst.port = be16(p + l4 + 2);
    std::size_t ulen = be16(p + l4 + 4);
    std::size_t pend = ulen >= 8 ? std::min(end, l4 + ulen) : end;
    std::string_view payload(reinterpret_cast<const char*>(p + l4 + 8), pend - l4 - 8);
    if (!udp_port_[src.port] && !udp_port_[dst.port] && !looks_like_top(payload)) return false;
    if (ip_id != 0 && duplicate(ts, ip_id, payload)) {
      a_.source_note(ts, ACode::duplicate_datagram,
                     "UDP datagram recorded twice: the same IPv4 identification " +
                         std::to_string(ip_id) + ", addresses, ports and payload as one " +
                         std::to_string(dup_gap_us_) + " us before; the copy is skipped",
                     record, l4 + 8);
      return true;
    }
    a_.datagram(ts, src, dst, payload, record, static_cast<std::uint32_t>(l4 + 8));
    return true;
  }
  if (proto == kIpProtoTcp) {
    if (end < l4 + 20) return bad(ts, record, l4, "TCP header cut short"), false;
    src.port = be16(p + l4);
    dst.port = be16(p + l4 + 2);
    std::uint32_t seq = be32(p + l4 + 4);
    std::size_t hl = (p[l4 + 12] >> 4) * 4u;
    if (hl < 20 || end < l4 + hl) return bad(ts, record, l4 + 12, "bad TCP header length"), false;
    bool syn = (p[l4 + 13] & 0x02) != 0;
    std::string_view payload(reinterpret_cast<const char*>(p + l4 + hl), end - l4 - hl);
    if (!tcp_port_[src.port] && !tcp_port_[dst.port]) {
      std::string a = src.text(), b = dst.text();
      std::string key = a < b ? a + " " + b : b + " " + a;
      if (!tcp_top_.count(key)) {
        if (!looks_like_top(payload)) return false;
        if (tcp_top_.size() < kMaxContentFlows) tcp_top_.insert(key);
      }
    }
    a_.segment(ts, src, dst, seq, syn, payload, record, static_cast<std::uint32_t>(l4 + hl));
    return true;
  }
  return false;
}

}  // namespace topdump
