// A client that does what PixEagle's Topotek interface does
// (alireza787b/PixEagle src/classes/gimbal_interface.py @ 0724458,
// GimbalInterface; facts carried over, no code): a query every 0.1 s, the
// tracking state (TRC) every fifth, else the spatial angles (GIC; the
// gimbal-body GAC branch of its loop is never reached: every count is a
// multiple of the GIC interval, 1), each #TP with source P and data 00, sent
// from an unbound socket it never reads; it reads what comes on UDP 9004
// (UdpClient::pixeagle) as text: angles from a packet that starts "#tp" and
// names GAC or GIC (12 hex after the identifier), the tracking state from
// the char after "TRC" and one more.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "driver_harness.hpp"
#include "top/frame.hpp"

class PixEagleClient : public DriverClient {
 public:
  struct Angles {
    double yaw, pitch, roll;  // deg, as the wire has them
  };
  std::vector<Angles> angles;  // what its parser took
  std::vector<int> states;     // each TRC state it read
  int trc_sent = 0, gic_sent = 0;
  int packets = 0, gia = 0, trc = 0;  // datagrams heard; GIA and TRC frames among them

  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    ++counter_;
    if (counter_ % 5 == 0) {
      out.push_back(query('D', "TRC"));
      ++trc_sent;
    } else {
      out.push_back(query('G', "GIC"));
      ++gic_sent;
    }
    return now_us + 100000;
  }

  void on_frame(const top::Frame& f, std::uint64_t) override {
    ++packets;
    const std::string_view p = f.raw;
    if (f.ident_view() == "GIA") ++gia;
    if (f.ident_view() == "TRC") ++trc;
    // _parse_angle_response: "#tp", then GAC or GIC anywhere in the text
    if (p.substr(0, 3) == "#tp" && p.find("OFT") == std::string_view::npos) {
      std::size_t at = p.find("GAC");
      if (at == std::string_view::npos) at = p.find("GIC");
      if (at != std::string_view::npos && at + 15 <= p.size())
        angles.push_back(
            {s16(p.substr(at + 3, 4)), s16(p.substr(at + 7, 4)), s16(p.substr(at + 11, 4))});
    }
    // _parse_tracking_response: the second char after "TRC"
    const std::size_t t = p.find("TRC");
    if (t != std::string_view::npos && t + 5 <= p.size() && p[t + 4] >= '0' && p[t + 4] <= '9')
      states.push_back(p[t + 4] - '0');
  }

 private:
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
