// What the capture generators of captures/ share (make_captures.cpp, the
// bundled captures; diagnosis_captures.cpp, the captures of
// docs/DIAGNOSES.md): the fixed addresses and times, a UDP exchange
// writer, checksums and socat's log format. Deterministic.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"
#include "top/frame.hpp"

namespace capture_kit {

using namespace pcapio;

constexpr std::int64_t T0 = 1714564800LL * 1000000;  // 2024-05-01T12:00:00Z
constexpr int kEn10mb = 1, kNull = 0, kRaw = 12, kSll = 113, kSll2 = 276;

inline const Ip4 kClient{192, 168, 144, 10};
inline const Ip4 kCamera{192, 168, 144, 108};
inline const Ip6 kClient6{0xfd, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x10};
inline const Ip6 kCamera6{0xfd, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x6c};

inline std::string F(const std::string& s) { return top::with_checksum(s); }

inline std::string dir;
inline std::string path(const char* name) { return dir + "/" + name; }

// A UDP exchange writer for one link type.
struct Udp {
  PcapWriter w;
  int dlt;
  std::uint16_t cport, dport;
  std::vector<std::uint16_t> vlans;
  bool v6 = false;
  std::vector<std::pair<std::int64_t, std::string>> pk;  // written in time order
  Udp(const char* name, int d, std::uint16_t cp, std::uint16_t dp)
      : w(path(name), d), dlt(d), cport(cp), dport(dp) {}
  ~Udp() {
    std::stable_sort(pk.begin(), pk.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [t, b] : pk) w.write(t, b);
  }
  std::string wrap(const std::string& ip) {
    switch (dlt) {
      case kEn10mb:
        return eth(ip, vlans);
      case kNull:
        return null_lo(ip);
      case kSll:
        return sll(ip);
      case kSll2:
        return sll2(ip);
      default:
        return ip;
    }
  }
  void up(std::int64_t ms, const std::string& payload) {
    std::string ip = v6 ? udp6(kClient6, kCamera6, cport, dport, payload)
                        : udp4(kClient, kCamera, cport, dport, payload);
    pk.emplace_back(T0 + ms * 1000, wrap(ip));
  }
  void down(std::int64_t ms, const std::string& payload) {
    std::string ip = v6 ? udp6(kCamera6, kClient6, dport, cport, payload)
                        : udp4(kCamera, kClient, dport, cport, payload);
    pk.emplace_back(T0 + ms * 1000, wrap(ip));
  }
  // `request` (without its checksum) at `ms`, echoed with the addresses
  // swapped `after` ms later.
  void echoed(std::int64_t ms, std::int64_t after, std::string request) {
    up(ms, F(request));
    std::swap(request[3], request[4]);
    down(ms + after, F(request));
  }
};

inline std::string gac(int i) {
  char b[16];
  std::snprintf(b, sizeof b, "%04X%04X%04X", (i * 25) & 0xFFFF, (0x10000 - 300 + i) & 0xFFFF, 0);
  return F(std::string("#TPGUCrGAC") + b);
}

// --- serial logs ------------------------------------------------------------

inline std::string socat_header(char dirc, int ms, std::size_t len) {
  char b[96];
  std::snprintf(b, sizeof b, "%c 2024/05/01 12:00:%02d.%06d000  length=%zu from=0 to=%zu\n", dirc,
                ms / 1000, (ms % 1000) * 1000, len, len - 1);
  return b;
}

inline std::string socat_text(const std::string& bytes) {
  std::string o;
  for (char ch : bytes) {
    auto c = static_cast<unsigned char>(ch);
    if (c == '\r')
      o += "\\r";
    else if (c == '\n')
      o += '\n';
    else if (c < 0x20 || c >= 0x7f)
      o += '.';
    else
      o += ch;
  }
  return o;
}

inline std::string socat_hex(const std::string& bytes) {
  std::string o;
  for (std::size_t i = 0; i < bytes.size(); i += 16) {
    std::string hex, asc;
    for (std::size_t j = i; j < i + 16 && j < bytes.size(); ++j) {
      char b[4];
      auto c = static_cast<unsigned char>(bytes[j]);
      std::snprintf(b, sizeof b, " %02x", c);
      hex += b;
      asc += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '.';
    }
    hex.resize(48, ' ');
    o += hex + "  " + asc + "\n";
  }
  return o + "--\n";
}

// The captures each diagnosis fires on, and their healthy counterparts
// (diagnosis_captures.cpp).
void diagnosis_captures();

}  // namespace capture_kit
