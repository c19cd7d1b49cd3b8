// A client that does what PixEagle's Topotek interface does
// (alireza787b/PixEagle src/classes/gimbal_interface.py @ 3bea324,
// GimbalInterface, the version the pixeagle driver profile reads; facts
// carried over, no code): every 0.1 s cycle the tracking state (TRC) when
// the cycle is a fifth, the gimbal-body angles (GAC) when a third, and the
// spatial angles (GIC) always (_query_loop: "each due family must run"),
// each #TP with source P and data 00, sent from an unbound socket it never
// reads. It reads what comes on UDP 9004 (UdpClient::pixeagle) and takes a
// frame only as _validated_frame passes it: at least 12 bytes, the last two
// the uppercase checksum of the rest; TRC as #TP or #tp, then DP2, r or w,
// 14 bytes; GAC, GIC, GIA as #tpGPC, r or w, 12 hex, 24 bytes; nothing else.
// Only GAC gives angles (_parse_gimbal_packet); GIC and GIA are kept as
// spatial diagnostics; TRC gives a state when its data char 0 is 0, 1 or 2.
// (The 0724458 version it replaces asked GIC or TRC alone and read angles
// from GAC or GIC anywhere in a "#tp" packet.)
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "driver_harness.hpp"
#include "top/frame.hpp"
#include "top/text.hpp"

class PixEagleClient : public DriverClient {
 public:
  struct Angles {
    double yaw, pitch, roll;  // deg, as the wire has them
    std::uint64_t t_us;       // when it took them
  };
  std::vector<Angles> angles;  // what its parser took (GAC only)
  std::vector<int> states;     // each TRC state it read
  int spatial = 0;             // GIC or GIA frames kept as diagnostics
  int trc_sent = 0, gac_sent = 0, gic_sent = 0;
  int packets = 0, gia = 0, trc = 0;  // frames heard; GIA and TRC frames among them

  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    ++counter_;
    if (counter_ % 5 == 0) {
      out.push_back(query('D', "TRC"));
      ++trc_sent;
    }
    if (counter_ % 3 == 0) {
      out.push_back(query('G', "GAC"));
      ++gac_sent;
    }
    out.push_back(query('G', "GIC"));
    ++gic_sent;
    return now_us + 100000;
  }

  void on_frame(const top::Frame& f, std::uint64_t now_us) override {
    ++packets;
    if (f.ident_view() == "GIA") ++gia;
    if (f.ident_view() == "TRC") ++trc;
    const std::string_view p = f.raw;
    if (!valid(p)) return;
    const std::string_view cmd = p.substr(7, 3);
    if (cmd == "GAC") {
      angles.push_back({s16(p.substr(10, 4)), s16(p.substr(14, 4)), s16(p.substr(18, 4)), now_us});
    } else if (cmd == "TRC") {
      if (p[10] >= '0' && p[10] <= '2' && p[11] >= '0' && p[11] <= '9')
        states.push_back(p[11] - '0');
    } else {
      ++spatial;
    }
  }

 private:
  // _validated_frame (the source IP check is the harness's: one host).
  static bool valid(std::string_view p) {
    if (p.size() < 12) return false;
    unsigned sum = 0;
    for (char c : p.substr(0, p.size() - 2)) sum += static_cast<unsigned char>(c);
    char cs[3];
    std::snprintf(cs, sizeof cs, "%02X", sum & 0xFF);
    if (p.substr(p.size() - 2) != std::string_view(cs, 2)) return false;
    const std::string_view cmd = p.substr(7, 3);
    const bool rw = p[6] == 'r' || p[6] == 'w';
    if (cmd == "TRC")
      return (p.substr(0, 3) == "#TP" || p.substr(0, 3) == "#tp") && p.substr(3, 3) == "DP2" &&
             rw && p.size() == 14;
    if (cmd != "GAC" && cmd != "GIC" && cmd != "GIA") return false;
    if (p.substr(0, 6) != "#tpGPC" || !rw || p.size() != 24) return false;
    for (char c : p.substr(10, 12))
      if (top::hex_value(c) < 0) return false;
    return true;
  }
  std::string query(char dst, std::string_view ident) const {
    return top::build_frame({.header = top::Header::fixed,
                             .src = client,
                             .dst = dst,
                             .control = 'r',
                             .ident = ident,
                             .data = "00"});
  }
  static double s16(std::string_view h) {
    int v = 0;
    for (char c : h) v = v * 16 + top::hex_value(c);
    return static_cast<std::int16_t>(v) / 100.0;
  }
  std::uint64_t counter_ = 0;
};
