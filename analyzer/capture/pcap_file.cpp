// libpcap sources: files (pcap and pcapng) and live interfaces.
#include <fcntl.h>
#include <pcap/pcap.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>

#include "capture/sources.hpp"

namespace topdump {

std::int64_t now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::optional<std::int64_t> parse_time(std::string_view s) {
  if (s.empty()) return std::nullopt;
  auto digits = [&](std::size_t at, std::size_t n, int& out) {
    if (at + n > s.size()) return false;
    out = 0;
    for (std::size_t i = at; i < at + n; ++i) {
      if (s[i] < '0' || s[i] > '9') return false;
      out = out * 10 + (s[i] - '0');
    }
    return true;
  };
  if (s.size() >= 19 && s[4] == '-' && s[7] == '-' && (s[10] == 'T' || s[10] == ' ')) {
    int Y, M, D, h, m, sec;
    if (!digits(0, 4, Y) || !digits(5, 2, M) || !digits(8, 2, D) || !digits(11, 2, h) ||
        s[13] != ':' || !digits(14, 2, m) || s[16] != ':' || !digits(17, 2, sec))
      return std::nullopt;
    std::tm tm{};
    tm.tm_year = Y - 1900;
    tm.tm_mon = M - 1;
    tm.tm_mday = D;
    tm.tm_hour = h;
    tm.tm_min = m;
    tm.tm_sec = sec;
    std::int64_t us = static_cast<std::int64_t>(timegm(&tm)) * 1000000;
    std::size_t i = 19;
    if (i < s.size() && (s[i] == '.' || s[i] == ',')) {
      ++i;
      std::int64_t frac = 0, scale = 100000;
      while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
        if (scale > 0) frac += (s[i] - '0') * scale;
        scale /= 10;
        ++i;
      }
      us += frac;
    }
    if (i < s.size() && s[i] == 'Z') {
      ++i;
    } else if (i < s.size() && (s[i] == '+' || s[i] == '-')) {
      int oh, om;
      bool neg = s[i] == '-';
      if (!digits(i + 1, 2, oh)) return std::nullopt;
      std::size_t j = i + 3;
      if (j < s.size() && s[j] == ':') ++j;
      if (!digits(j, 2, om)) return std::nullopt;
      std::int64_t off = (oh * 3600 + om * 60) * std::int64_t{1000000};
      us += neg ? off : -off;
      i = j + 2;
    }
    if (i != s.size()) return std::nullopt;
    return us;
  }
  // epoch seconds
  std::int64_t whole = 0, frac = 0, scale = 100000;
  std::size_t i = 0;
  bool any = false;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9')
    whole = whole * 10 + (s[i++] - '0'), any = true;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
      if (scale > 0) frac += (s[i] - '0') * scale;
      scale /= 10;
      ++i;
      any = true;
    }
  }
  if (!any || i != s.size()) return std::nullopt;
  return whole * 1000000 + frac;
}

std::string format_time(std::int64_t us) {
  if (us == kNoTime) return "-";
  // the civil date by chrono's calendar (no gmtime_r and printf per line:
  // the text output prints one per frame)
  using namespace std::chrono;
  const sys_time<microseconds> tp{microseconds(us)};
  const auto day = floor<days>(tp);
  const year_month_day ymd{day};
  const hh_mm_ss<microseconds> hms{tp - day};
  const int y = static_cast<int>(ymd.year());
  if (y < 0 || y > 9999) {  // printf's form for years the fast path does not write
    char b[64];
    std::snprintf(b, sizeof b, "%04d-%02u-%02uT%02lld:%02lld:%02lld.%06lldZ", y,
                  static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()),
                  static_cast<long long>(hms.hours().count()),
                  static_cast<long long>(hms.minutes().count()),
                  static_cast<long long>(hms.seconds().count()),
                  static_cast<long long>(hms.subseconds().count()));
    return b;
  }
  char b[27];  // 2024-05-01T12:00:00.123456Z
  auto put = [&](int at, long long v, int digits) {
    for (int i = digits - 1; i >= 0; --i, v /= 10) b[at + i] = static_cast<char>('0' + v % 10);
  };
  put(0, y, 4);
  b[4] = '-';
  put(5, static_cast<unsigned>(ymd.month()), 2);
  b[7] = '-';
  put(8, static_cast<unsigned>(ymd.day()), 2);
  b[10] = 'T';
  put(11, hms.hours().count(), 2);
  b[13] = ':';
  put(14, hms.minutes().count(), 2);
  b[16] = ':';
  put(17, hms.seconds().count(), 2);
  b[19] = '.';
  put(20, hms.subseconds().count(), 6);
  b[26] = 'Z';
  return std::string(b, sizeof b);
}

// ---------------------------------------------------------------------------
// Dissection

namespace {
constexpr int kDltLoop = 108;
constexpr int kDltRaw1 = 12;
constexpr int kDltRaw2 = 14;
constexpr int kDltSll = 113;
constexpr int kDltSll2 = 276;
constexpr int kDltIpv4 = 228;
constexpr int kDltIpv6 = 229;

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
        ethertype = 0x0800;
      else if (af == 10 || af == 24 || af == 28 || af == 30)
        ethertype = 0x86DD;
      else
        return false;
      break;
    }
    case DLT_EN10MB: {
      if (n < 14) return bad(ts, record, 0, "Ethernet header cut short"), false;
      ethertype = be16(p + 12);
      off = 14;
      while (ethertype == 0x8100 || ethertype == 0x88A8 || ethertype == 0x9100) {
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
      ethertype = (p[0] >> 4) == 6 ? 0x86DD : 0x0800;
      break;
    default:
      return false;
  }
  if (ethertype != 0x0800 && ethertype != 0x86DD) return false;
  return ip(ts, p, n, off, record);
}

bool Dissector::ip(std::int64_t ts, const std::uint8_t* p, std::size_t n, std::size_t off,
                   std::uint64_t record) {
  // Reused from packet to packet (name stays empty): the stores below are
  // all that change.
  Endpoint& src = src_;
  Endpoint& dst = dst_;
  std::uint8_t proto = 0;
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
    std::uint16_t frag = be16(p + off + 6);
    proto = p[off + 9];
    if ((frag & 0x3FFF) != 0 && (proto == 17 || proto == 6))
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
    for (int hops = 0; hops < 8 && (proto == 0 || proto == 43 || proto == 60 || proto == 44);
         ++hops) {
      if (end < l4 + 8) return bad(ts, record, l4, "IPv6 extension header cut short"), false;
      if (proto == 44) return bad(ts, record, l4, "IPv6 fragment (not reassembled)"), false;
      std::uint8_t next = p[l4];
      l4 += (p[l4 + 1] + 1u) * 8u;
      proto = next;
    }
  } else {
    return bad(ts, record, off, "IP version " + std::to_string(version)), false;
  }
  if (proto == 17) {
    if (end < l4 + 8) return bad(ts, record, l4, "UDP header cut short"), false;
    src.port = be16(p + l4);
    dst.port = be16(p + l4 + 2);
    std::size_t ulen = be16(p + l4 + 4);
    std::size_t pend = ulen >= 8 ? std::min(end, l4 + ulen) : end;
    std::string_view payload(reinterpret_cast<const char*>(p + l4 + 8), pend - l4 - 8);
    if (!udp_port_[src.port] && !udp_port_[dst.port] && !looks_like_top(payload)) return false;
    a_.datagram(ts, src, dst, payload, record, static_cast<std::uint32_t>(l4 + 8));
    return true;
  }
  if (proto == 6) {
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
        if (tcp_top_.size() < kMaxConversations) tcp_top_.insert(key);
      }
    }
    a_.segment(ts, src, dst, seq, syn, payload, record, static_cast<std::uint32_t>(l4 + hl));
    return true;
  }
  return false;
}

// ---------------------------------------------------------------------------
// Files

bool read_serial_log(Input& in, Format f, Analyzer& a, const SourceOptions& o, std::string& error);

std::set<std::uint16_t> known_ports(bool tcp) {
  std::set<std::uint16_t> s;
  for (const top::PortSpec& p : top::known_ports())
    if (p.tcp == tcp) s.insert(p.port);
  return s;
}

namespace {

// A pipe, FIFO or terminal as a FILE: the bytes read for detection first,
// then the rest of the descriptor.
struct PipeCookie {
  int fd;
  std::string head;
  std::size_t at = 0;
};
ssize_t pipe_read(void* c, char* buf, std::size_t n) {
  auto& k = *static_cast<PipeCookie*>(c);
  if (k.at < k.head.size()) {
    std::size_t m = std::min(n, k.head.size() - k.at);
    std::memcpy(buf, k.head.data() + k.at, m);
    k.at += m;
    if (k.at == k.head.size()) std::string().swap(k.head), k.at = 0;
    return static_cast<ssize_t>(m);
  }
  for (;;) {
    ssize_t r = ::read(k.fd, buf, n);
    if (r >= 0 || errno != EINTR) return r;
  }
}
int pipe_close(void* c) {
  auto* k = static_cast<PipeCookie*>(c);
  int r = ::close(k->fd);
  delete k;
  return r;
}

// Our own FILE buffer: libpcap reads each record with two freads, and
// stdio's default 4 KiB buffer costs a read(2) every ~50 records (5% of
// topdump stats; 64 KiB to 1 MiB measure alike).
constexpr std::size_t kReadBuffer = std::size_t{1} << 16;

std::string hex32(std::string_view b) {
  char t[9];
  std::snprintf(t, sizeof t, "%02x%02x%02x%02x", static_cast<unsigned char>(b[0]),
                static_cast<unsigned char>(b[1]), static_cast<unsigned char>(b[2]),
                static_cast<unsigned char>(b[3]));
  return t;
}

bool is_pcap_magic(std::string_view h) {
  if (h.size() < 4) return false;
  std::uint32_t m;
  std::memcpy(&m, h.data(), 4);
  return m == 0xa1b2c3d4 || m == 0xd4c3b2a1 || m == 0xa1b23c4d || m == 0x4d3cb2a1;
}

}  // namespace

bool open_input(const std::string& path, Input& in, std::string& error) {
  in.name = path == "-" ? "stdin" : path;
  int fd = path == "-" ? ::dup(0) : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = in.name + ": cannot open: " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || S_ISDIR(st.st_mode)) {
    error = in.name + (S_ISDIR(st.st_mode) ? ": is a directory, not a capture file"
                                           : ": cannot open: " + std::string(std::strerror(errno)));
    ::close(fd);
    return false;
  }
  in.regular = S_ISREG(st.st_mode);
  in.size = in.regular ? static_cast<std::uint64_t>(st.st_size) : 0;
  in.buffer.reset(new char[kReadBuffer]);
  if (in.regular) {
    in.file = ::fdopen(fd, "rb");
    if (!in.file) {
      error = in.name + ": cannot open: " + std::strerror(errno);
      ::close(fd);
      return false;
    }
    std::setvbuf(in.file, in.buffer.get(), _IOFBF, kReadBuffer);
    in.head.resize(kInputHead);
    in.head.resize(std::fread(in.head.data(), 1, kInputHead, in.file));
    if (std::ferror(in.file) || std::fseek(in.file, 0, SEEK_SET) != 0) {
      error = in.name + ": cannot read: " + std::strerror(errno);
      return false;
    }
    return true;
  }
  // Not seekable: keep what detection reads and hand it out again first.
  std::string head(kInputHead, '\0');
  std::size_t got = 0;
  while (got < kInputHead) {
    ssize_t r = ::read(fd, head.data() + got, kInputHead - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      error = in.name + ": cannot read: " + std::strerror(errno);
      ::close(fd);
      return false;
    }
    if (r == 0) break;
    got += static_cast<std::size_t>(r);
  }
  head.resize(got);
  in.head = head;
  auto* cookie = new PipeCookie{fd, std::move(head)};
  in.file =
      ::fopencookie(cookie, "rb", cookie_io_functions_t{pipe_read, nullptr, nullptr, pipe_close});
  if (!in.file) {
    error = in.name + ": cannot open: " + std::strerror(errno);
    pipe_close(cookie);
    return false;
  }
  std::setvbuf(in.file, in.buffer.get(), _IOFBF, kReadBuffer);
  return true;
}

bool make_seekable(Input& in, std::string& error) {
  if (in.regular) return true;
  std::FILE* t = std::tmpfile();
  if (!t) {
    error = in.name + ": cannot spool to a temporary file: " + std::strerror(errno);
    return false;
  }
  std::vector<char> b(kReadBuffer);
  std::size_t n;
  while ((n = std::fread(b.data(), 1, b.size(), in.file)) > 0) {
    if (std::fwrite(b.data(), 1, n, t) != n) {
      error = in.name + ": cannot spool to a temporary file: " + std::strerror(errno);
      std::fclose(t);
      return false;
    }
  }
  const bool bad = std::ferror(in.file) != 0;
  std::fclose(in.file);
  in.file = t;
  if (bad) {
    error = in.name + ": read error: " + std::strerror(errno);
    return false;
  }
  in.regular = true;
  in.size = static_cast<std::uint64_t>(std::ftell(t));
  std::rewind(t);
  return true;
}

std::optional<std::string> damaged_capture(std::string_view head) {
  if (head.size() < 12 || is_pcap_magic(head) || head.substr(0, 4) == "\x0a\x0d\x0d\x0a")
    return std::nullopt;
  auto at = [&](std::size_t i) { return static_cast<unsigned char>(head[i]); };
  // pcap: version 2.4 after the magic, in either byte order
  const bool pcap_version = (at(4) == 2 && at(5) == 0 && at(6) == 4 && at(7) == 0) ||
                            (at(4) == 0 && at(5) == 2 && at(6) == 0 && at(7) == 4);
  // pcapng: the section header's byte-order magic after the block length
  const bool ng_order =
      head.substr(8, 4) == "\x4d\x3c\x2b\x1a" || head.substr(8, 4) == "\x1a\x2b\x3c\x4d";
  if (!pcap_version && !ng_order) return std::nullopt;
  return "offset 0: magic number " + hex32(head) + " is not a pcap or pcapng magic, but " +
         (pcap_version ? "bytes 4-7 are a pcap file header's version 2.4"
                       : "bytes 8-11 are a pcapng section header's byte-order magic") +
         ": a damaged capture (--format raw reads it as a raw serial dump)";
}

namespace {

// The offset of the `record`-th packet block of a pcapng file (blocks of
// type 2, 3 and 6), walking the block lengths; or the file size when the
// walk ends first.
std::uint64_t pcapng_block_offset(std::FILE* f, std::uint64_t record) {
  if (std::fseek(f, 0, SEEK_SET) != 0) return 0;
  std::uint64_t at = 0, packets = 0;
  bool big = false;
  unsigned char h[12];
  while (std::fread(h, 1, 8, f) == 8) {
    auto u32 = [&](const unsigned char* p) {
      return big ? std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 |
                       std::uint32_t{p[2]} << 8 | p[3]
                 : std::uint32_t{p[3]} << 24 | std::uint32_t{p[2]} << 16 |
                       std::uint32_t{p[1]} << 8 | p[0];
    };
    if (std::memcmp(h, "\x0a\x0d\x0d\x0a", 4) == 0) {
      if (std::fread(h + 8, 1, 4, f) != 4) break;
      big = h[8] == 0x1a;
    }
    std::uint32_t type = u32(h), len = u32(h + 4);
    if (type == 2 || type == 3 || type == 6) {
      if (++packets == record) return at;
    }
    if (len < 12 || len % 4 != 0) return at;
    at += len;
    if (std::fseek(f, static_cast<long>(at), SEEK_SET) != 0) break;
  }
  return at;
}

// The finding a libpcap read error stands for.
ACode code_of_pcap_error(std::string_view e) {
  if (e.find("invalid packet capture length") != std::string_view::npos) return ACode::bad_caplen;
  if (e.find("has a length of") != std::string_view::npos ||
      e.find("total length in header and trailer") != std::string_view::npos)
    return ACode::bad_block_length;
  if (e.find("a packet arrived on interface") != std::string_view::npos)
    return ACode::unknown_interface;
  if (e.find("truncated") != std::string_view::npos) return ACode::truncated_file;
  return ACode::bad_block;
}

}  // namespace

bool read_file(const std::string& path, Format format, Analyzer& a, const SourceOptions& o,
               std::string& error, InputInfo* info) {
  Input in;
  if (!open_input(path, in, error)) return false;
  return read_input(in, format, a, o, error, info);
}

bool read_input(Input& in, Format format, Analyzer& a, const SourceOptions& o, std::string& error,
                InputInfo* info) {
  const std::string& path = in.name;
  const bool ng_magic = in.head.size() >= 4 && in.head.compare(0, 4, "\x0a\x0d\x0d\x0a", 4) == 0;
  const bool pcap_magic = is_pcap_magic(in.head);
  if (format == Format::automatic) {
    if (auto why = damaged_capture(in.head)) {
      error = path + ": " + *why;
      return false;
    }
    format = detect_format(in.head);
  } else if ((format == Format::pcap || format == Format::pcapng) && !pcap_magic && !ng_magic) {
    error = path + ": offset 0: " +
            (in.head.size() < 4 ? "the file holds " + std::to_string(in.head.size()) + " bytes"
                                : "magic number " + hex32(in.head)) +
            ", not a " + std::string(to_string(format)) + " file";
    return false;
  } else if ((format == Format::pcap && ng_magic) || (format == Format::pcapng && pcap_magic)) {
    error = path + ": offset 0: --format " + std::string(to_string(format)) + " but this is a " +
            (ng_magic ? "pcapng" : "pcap") + " file";
    return false;
  }
  InputInfo what{path, format, {}};
  if (format != Format::pcap && format != Format::pcapng) {
    if (info) *info = what;
    if (o.on_input) o.on_input(what);
    return read_serial_log(in, format, a, o, error);
  }

  const std::size_t header = format == Format::pcapng ? 28 : 24;
  if (in.head.size() < header) {
    error = path + ": offset 0: the " + std::string(to_string(format)) +
            " file header is cut short (" + std::to_string(in.head.size()) + " of " +
            std::to_string(header) + " bytes)";
    return false;
  }
  char errbuf[PCAP_ERRBUF_SIZE] = {0};
  // pcap_close() closes the file; the Input's buffer outlives it.
  std::FILE* file = in.file;
  pcap_t* p = pcap_fopen_offline_with_tstamp_precision(file, PCAP_TSTAMP_PRECISION_MICRO, errbuf);
  if (!p) {
    error = path + ": offset 0: " + errbuf;
    return false;
  }
  in.file = nullptr;
  int dlt = pcap_datalink(p);
  const char* dlt_name = pcap_datalink_val_to_name(dlt);
  what.link = dlt_name ? dlt_name : std::to_string(dlt);
  if (info) *info = what;
  if (o.on_input) o.on_input(what);
  if (!Dissector::supported(dlt)) {
    a.source_note(kNoTime, ACode::unsupported_link,
                  path + ": link type " + std::to_string(dlt) + " (" + (dlt_name ? dlt_name : "?") +
                      ") is not dissected",
                  0, 0);
    pcap_close(p);
    return true;
  }
  const std::uint64_t total = in.size;
  const bool ng = format == Format::pcapng;
  // pcap_loop hands each record to the callback from inside libpcap's read
  // loop (pcap_next_ex costs a call chain per record). pcap: records follow
  // a 24-byte header, each with a 16-byte header, so the file offset of a
  // record is known without asking the stream (an lseek per record).
  // pcapng: found by walking the blocks after a failure.
  struct Reader {
    Dissector dis;
    Analyzer& a;
    const SourceOptions& o;
    int dlt;
    FILE* fp;
    std::uint64_t total;
    std::uint64_t at = 24;
    std::uint64_t record = 0;
    pcap_t* pcap = nullptr;
  } rd{Dissector(a, o), a, o, dlt, in.regular ? file : nullptr, total};
  rd.pcap = p;
  const int rc = pcap_loop(
      p, -1,
      [](u_char* user, const pcap_pkthdr* h, const u_char* data) {
        auto& r = *reinterpret_cast<Reader*>(user);
        ++r.record;
        r.at += 16 + h->caplen;
        const std::int64_t ts = static_cast<std::int64_t>(h->ts.tv_sec) * 1000000 + h->ts.tv_usec;
        if (r.o.packet)
          r.o.packet(r.dlt, ts, std::string_view(reinterpret_cast<const char*>(data), h->caplen),
                     h->len, r.record);
        r.a.record(r.dis.packet(r.dlt, ts, data, h->caplen, h->len, r.record));
        if (r.a.done()) pcap_breakloop(r.pcap);  // -c: the frames asked for are in
        if (r.o.progress && (r.record & 0xFFFF) == 0 && r.fp)
          r.o.progress(static_cast<std::uint64_t>(std::ftell(r.fp)), r.total);
      },
      reinterpret_cast<u_char*>(&rd));
  if (rc == PCAP_ERROR) {
    const std::string why = pcap_geterr(p);
    std::uint64_t at = rd.at;
    std::string where;
    if (!ng) {
      where = "at file offset " + std::to_string(at);
    } else if (in.regular) {
      at = pcapng_block_offset(file, rd.record + 1);
      where = "in the block at file offset " + std::to_string(at);
    } else {
      at = 0;
      where = "(a pipe: offset unknown)";
    }
    a.source_note(kNoTime, code_of_pcap_error(why),
                  path + ": record " + std::to_string(rd.record + 1) + " " + where + ": " + why,
                  rd.record + 1, at);
  }
  pcap_close(p);
  if (o.progress) o.progress(total, total);
  return true;
}

// ---------------------------------------------------------------------------
// Live

namespace {
struct LiveCtx {
  Analyzer* a;
  Dissector* dis;
  int dlt;
  std::uint64_t record = 0;
};
void on_packet(u_char* user, const pcap_pkthdr* h, const u_char* data) {
  auto* c = reinterpret_cast<LiveCtx*>(user);
  ++c->record;
  std::int64_t ts = static_cast<std::int64_t>(h->ts.tv_sec) * 1000000 + h->ts.tv_usec;
  c->a->record(c->dis->packet(c->dlt, ts, data, h->caplen, h->len, c->record));
}
}  // namespace

bool capture_live(const std::string& iface, const std::string& bpf, Analyzer& a,
                  const SourceOptions& o, const std::atomic<bool>& stop, std::string& error,
                  bool& permission) {
  permission = false;
  char errbuf[PCAP_ERRBUF_SIZE] = {0};
  pcap_t* p = pcap_create(iface.c_str(), errbuf);
  if (!p) {
    error = iface + ": " + errbuf;
    return false;
  }
  pcap_set_snaplen(p, 65535);
  pcap_set_promisc(p, 0);
  pcap_set_timeout(p, 100);
  pcap_set_immediate_mode(p, 1);
  int rc = pcap_activate(p);
  if (rc < 0) {
    permission = rc == PCAP_ERROR_PERM_DENIED;
    error = iface + ": " + pcap_statustostr(rc) + ": " + pcap_geterr(p);
    pcap_close(p);
    return false;
  }
  if (!bpf.empty()) {
    bpf_program prog;
    if (pcap_compile(p, &prog, bpf.c_str(), 1, PCAP_NETMASK_UNKNOWN) != 0 ||
        pcap_setfilter(p, &prog) != 0) {
      error = "filter \"" + bpf + "\": " + pcap_geterr(p);
      pcap_close(p);
      return false;
    }
    pcap_freecode(&prog);
  }
  int dlt = pcap_datalink(p);
  if (!Dissector::supported(dlt)) {
    error = iface + ": link type " + std::to_string(dlt) + " is not dissected";
    pcap_close(p);
    return false;
  }
  Dissector dis(a, o);
  LiveCtx ctx{&a, &dis, dlt};
  // Non-blocking reads behind our own poll: pcap_dispatch in immediate mode
  // may block forever on a quiet interface, and SIGINT must end the loop.
  int fd = pcap_get_selectable_fd(p);
  if (fd < 0 || pcap_setnonblock(p, 1, errbuf) != 0) {
    error = iface + ": cannot poll the capture: " + errbuf;
    pcap_close(p);
    return false;
  }
  while (!stop.load()) {
    pollfd pfd{fd, POLLIN, 0};
    if (poll(&pfd, 1, 100) < 0 && errno != EINTR) {
      error = iface + ": poll: " + std::strerror(errno);
      pcap_close(p);
      return false;
    }
    int n = pcap_dispatch(p, -1, on_packet, reinterpret_cast<u_char*>(&ctx));
    if (n == PCAP_ERROR) {
      error = iface + ": " + pcap_geterr(p);
      pcap_close(p);
      return false;
    }
    a.flush_streams();
  }
  pcap_close(p);
  return true;
}

}  // namespace topdump
