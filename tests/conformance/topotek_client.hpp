// A client that does what ArduPilot's Topotek mount driver does
// (AP_Mount_Topotek, MNT1_TYPE 12), written from the facts in
// docs/sources/ardupilot.md section 1 (no code of the driver carried over):
// the tick and the round robin from the driver's profile
// (conformance/drivers, profile ardupilot-topotek): a 10 Hz tick; each tick
// LAT/LON/ALT/AZI; a round robin of ten steps, one a tick, so each once a
// second: VSN (step 0, until answered), GIA enable (2), SDC (4), TRC read
// (6), PA2 (8, until answered); angle targets GAY/GIP/GIR
// (#tp, 6 chars, speed 63) or a YPR rate at 10 Hz while not tracking; PTZ 00
// three times when the rates go to zero; UTC after an SDC reply that is not
// NNNN (at most 7 times); REC on/off; TRC 02 + LOC to track, TRC 01/00 to
// cancel; LRF 03/00 to switch the rangefinder on and off. It reads GIA,
// REC, SDC, LRF, TRC, VSN and PA2 the way the driver does (section 1.3; the
// LRF distance as AP_Mount_Topotek.cpp @ d4209711 gimbal_dist_info_analyse()
// reads it).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "driver_harness.hpp"
#include "drivers/profile.hpp"
#include "top/frame.hpp"
#include "top/text.hpp"

class TopotekClient : public DriverClient {
 public:
  // What the vehicle asks for (set by the test between ticks).
  bool rate_mode = false;
  double yaw = 0, pitch = 0, roll = 0;                 // angle targets, deg, pitch up positive
  double yaw_rate = 0, pitch_rate = 0, roll_rate = 0;  // deg/s, pitch up positive

  // What the driver learnt.
  struct Attitude {
    std::uint64_t t_us;
    double yaw, pitch, roll;  // deg, pitch up positive (the wire's negated)
  };
  std::vector<Attitude> attitude;  // from 12-char GIA frames
  int short_gia = 0;               // GIA frames without 12 data chars (the enable's echo): the
                                   // driver, which checks no length, would read garbage from them
  bool version_parsed = false;
  int version[3] = {0, 0, 0};
  std::string model_name;
  bool sd_parsed = false, sd_ok = false;
  int utc_sent = 0;
  std::vector<bool> recording;     // each REC frame's state
  std::vector<char> track_states;  // each TRC frame's data char 1
  char track_state = '0';
  bool tracking = false;   // the driver's _is_tracking
  double distance_m = -1;  // the driver's _measure_dist_m: -1 until a range, or after ERR
  int lrf = 0;             // LRF frames read
  int oft = 0, ere = 0, frames = 0;

  // Commands as the driver's API gives them; sent at the next tick.
  void record(bool on) { pending_.push_back(fixed('D', 'w', "REC", on ? 1 : 0)); }
  // A tracking point at the image centre (section 1.2: a 60-pixel box).
  void track_centre() {
    if (track_state == '0') pending_.push_back(fixed('D', 'w', "TRC", 2));
    pending_.push_back(loc(0, 0, 62, 111, 0x0009));
  }
  void cancel_tracking() { pending_.push_back(fixed('D', 'w', "TRC", track_state == '2' ? 1 : 0)); }
  // set_rangefinder_enable(): 03 continuous measurement, 00 stop, to M.
  void rangefinder(bool on) { pending_.push_back(fixed('M', 'w', "LRF", on ? 3 : 0)); }

  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    out.insert(out.end(), pending_.begin(), pending_.end());
    pending_.clear();
    if (utc_due_) {
      utc_due_ = false;
      if (utc_sent < 7) out.push_back(utc()), ++utc_sent;
    }
    position(out);
    // The 1 Hz round robin as the driver's profile gives it
    // (conformance/drivers: its steps, identifiers and the ones sent until
    // answered), one step a tick.
    const int step = static_cast<int>(++step_ % 10);
    for (const drivers::Sent& q : profile().sends)
      if (q.slot == step && !(q.until_answered && answered(q.ident)))
        out.push_back(frame(top::Header::fixed, q.dst, q.control, q.ident, q.data));
    if (!tracking) targets(out);
    return now_us + std::uint64_t{profile().tick_ms} * 1000;
  }
  static const drivers::Profile& profile() {
    static const drivers::Profile* p = drivers::find_profile("ardupilot-topotek");
    return *p;
  }

  void on_frame(const top::Frame& f, std::uint64_t now_us) override {
    if (!f.ok()) return;
    ++frames;
    const std::string_view id = f.ident_view(), d = f.data();
    if (id == "ERE") ++ere;
    if (id == "OFT") ++oft;
    if (id == "GIA") {
      if (d.size() != 12) {
        ++short_gia;
        return;
      }
      attitude.push_back({now_us, s16(d.substr(0, 4)) * 0.01, -s16(d.substr(4, 4)) * 0.01,
                          s16(d.substr(8, 4)) * 0.01});
    } else if (id == "REC" && d.size() >= 2) {
      recording.push_back(d[0] == '1' || d[1] == '1');
    } else if (id == "SDC" && d.size() >= 4) {
      sd_parsed = true;
      sd_ok = d.substr(0, 4) != "NNNN";
      if (sd_ok) utc_due_ = true;
    } else if (id == "TRC" && d.size() >= 2) {
      track_state = d[1];
      track_states.push_back(d[1]);
      if (d[1] == '2') tracking = true;
      if (d[1] == '0' || d[1] == '1') tracking = false;
    } else if (id == "VSN") {
      parse_version(d);
    } else if (id == "PA2" && !d.empty()) {
      model_name = std::string(d.substr(0, 15));
    } else if (id == "LRF") {
      ++lrf;
      distance_m = distance(f.raw);
    }
  }

 private:
  std::uint64_t step_ = 0;
  // What the driver stops asking once parsed (Sent::until_answered).
  bool answered(std::string_view ident) const {
    return (ident == "VSN" && version_parsed) || (ident == "PA2" && !model_name.empty());
  }
  int stops_ = 0;
  bool utc_due_ = false;
  std::vector<std::string> pending_;

  static int s16(std::string_view h) {
    return static_cast<std::int16_t>(std::stoi(std::string(h), nullptr, 16));
  }
  static std::string hex4(double centi) {
    char b[8];
    std::snprintf(b, sizeof b, "%04X",
                  static_cast<unsigned>(static_cast<std::uint16_t>(std::lround(centi))));
    return b;
  }
  static std::string hex2(long v) {
    char b[4];
    std::snprintf(b, sizeof b, "%02X", static_cast<unsigned>(static_cast<std::uint8_t>(v)));
    return b;
  }
  std::string frame(top::Header h, char dst, char ctl, std::string_view id,
                    std::string_view data) const {
    return top::build_frame(
        {.header = h, .src = client, .dst = dst, .control = ctl, .ident = id, .data = data});
  }
  // The driver's only #TP sender: one byte as 2 hex chars.
  std::string fixed(char dst, char ctl, std::string_view id, int v) const {
    return frame(top::Header::fixed, dst, ctl, id, hex2(v));
  }
  std::string var(char dst, std::string_view id, std::string_view data) const {
    return frame(top::Header::variable, dst, 'w', id, data);
  }
  std::string loc(int x, int y, int w, int h, int mode) const {
    std::string d;
    for (int v : {x, y, w, h, mode}) {
      d.push_back(static_cast<char>((v >> 8) & 0xFF));
      d.push_back(static_cast<char>(v & 0xFF));
    }
    return var('D', "LOC", d);
  }
  std::string utc() const {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char b[80];
    std::snprintf(b, sizeof b, "%02d%02d%02d%02d%02d%02d", tm.tm_hour, tm.tm_min, tm.tm_sec,
                  tm.tm_mday, tm.tm_mon + 1, tm.tm_year % 100);
    return var('D', "UTC", b);
  }
  // A fixed position: 35.335343 N, 138.727 E, 123.4 m, heading 45.
  void position(std::vector<std::string>& out) const {
    out.push_back(var('D', "LAT", "N3520.1206"));
    out.push_back(var('D', "LON", "E13843.6200"));
    out.push_back(var('D', "ALT", "000123.4"));
    out.push_back(var('D', "AZI", "045.0"));
  }
  void targets(std::vector<std::string>& out) {
    if (!rate_mode) {
      stops_ = 0;
      // Yaw body frame, pitch negated (down positive on the wire), speed 99.
      out.push_back(var('G', "GAY", hex4(yaw * 100) + "63"));
      out.push_back(var('G', "GIP", hex4(-pitch * 100) + "63"));
      out.push_back(var('G', "GIR", hex4(roll * 100) + "63"));
      return;
    }
    if (yaw_rate == 0 && pitch_rate == 0 && roll_rate == 0) {
      if (stops_ < 3) out.push_back(fixed('G', 'w', "PTZ", 0)), ++stops_;
      return;
    }
    stops_ = 0;
    // deg/s x 1.220740379, +-99, pitch negated (PR #29002).
    auto rate = [](double r) {
      return hex2(std::lround(std::fmax(-99, std::fmin(99, r * 1.220740379))));
    };
    out.push_back(var('G', "YPR", rate(yaw_rate) + rate(-pitch_rate) + rate(roll_rate)));
  }
  // The driver's buffer holds the frame from '#': data starts at byte 10.
  // ERR in data chars 0-2 is no range; otherwise the digits of "12345.6" are
  // read at chars 0-4 and 6, char 5 skipped, whatever the length char says
  // (each as a hex nibble, as the driver converts them).
  static double distance(std::string_view raw) {
    auto at = [&](std::size_t i) { return 10 + i < raw.size() ? raw[10 + i] : '\0'; };
    if (at(0) == 'E' && at(1) == 'R' && at(2) == 'R') return -1;
    auto nib = [&](std::size_t i) { return std::max(0, top::hex_value(at(i))); };
    return nib(0) * 10000.0 + nib(1) * 1000.0 + nib(2) * 100.0 + nib(3) * 10.0 + nib(4) +
           nib(6) * 0.1;
  }
  // Numbers ended by '.', at most three; without a '.', three single digits.
  void parse_version(std::string_view d) {
    int parts[3] = {0, 0, 0}, n = 0, cur = 0;
    if (d.find('.') == std::string_view::npos) {
      for (std::size_t i = 0; i < 3 && i < d.size(); ++i) parts[i] = top::hex_value(d[i]);
      n = 3;
    } else {
      for (char c : d) {
        if (n == 3) break;
        if (c == '.') {
          parts[n++] = cur;
          cur = 0;
        } else {
          cur = cur * 10 + top::hex_value(c);
        }
      }
    }
    for (int i = 0; i < 3; ++i) version[i] = parts[i];
    version_parsed = n > 0;
  }
};
