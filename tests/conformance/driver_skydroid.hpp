// A client that does what ArduPilot's SkyDroid mount driver does
// (AP_Mount_SkyDroid, PR #34155, https://github.com/ArduPilot/ardupilot/pull/34155),
// written from the facts of docs/sources/ardupilot.md section 2, not from
// its code: what it sends and when, and how it reads the replies.
//
// Sends: GSY and GSP every update (about 50 Hz) at 0.5 deg/s per LSB, in
// angle mode closing its own loop on the GAC attitude (kP 1 deg/s per deg,
// saturating at 63.5 deg/s, dead zone 0.05 deg; GSY carries the negated yaw
// rate: "a positive GSY value moves yaw LEFT"), both 00 while not healthy;
// PTZ 06 (follow) first; FAI (14 data chars, #tp) at 10 Hz; a 1 Hz round
// robin of ten 100 ms steps: 0 VER (until parsed), 1 TIM, 2 GAA 32 (50 Hz),
// 3 MOD (until parsed), 4 SDC, 6 FAE. Camera commands on request.
// Parses: GAC (>= 12 data chars: yaw, pitch up positive, roll, int16 in
// 0.01 deg), REC (data char 1), SDC (>= 10 chars, all 0: no card), VER
// ("V1.0.78"), MOD (the model name, which the driver cuts at 7 chars).
//
// For topconf drive (issue 50): the drive contract's intents (rate, angle,
// stop, centre, camera, identity, clock), its beliefs, and the known bugs
// of drive_client/drive_api.hpp (`bugs`). Without a bug it is a good
// driver: TIM's month 1-based (the PR's is 0-based: month-zero-based),
// zero rates sent three times, not every update, and a runaway guard.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include "drive_client/drive_api.hpp"
#include "drive_client/intents.hpp"
#include "driver_harness.hpp"
#include "top/top.hpp"

class SkyDroidDriver : public DriverClient {
 public:
  // Targets of the angle loop (deg, pitch up positive).
  double target_yaw = 0, target_pitch = -30;
  // Rate mode (deg/s, pitch up, yaw right): GSY/GSP from the rates, not the loop.
  bool rate_mode = false;
  double yaw_rate = 0, pitch_rate = 0;
  // No motion command until the first motion intent (topkit_drive_client).
  bool idle = false;
  // The runaway guard on rates (drive::RunawayGuard): on in topconf
  // drive's clients; off where a test watches a device turn the wrong way.
  bool guard = false;
  drive::Bugs bugs;
  // A camera command to send at a time after the start.
  struct Timed {
    std::uint64_t at_us;
    char dst;
    std::string ident, data;
    bool sent = false;
  };
  std::vector<Timed> camera;

  // What the driver learnt.
  struct Attitude {
    std::uint64_t t_us;
    double yaw, pitch, roll;
  };
  std::vector<Attitude> attitude;  // from full GAC frames
  std::string version;             // "1.0.78" from "V1.0.78"
  std::string model;
  std::optional<bool> sd_present;
  std::vector<bool> recording;      // every REC state parsed, in order
  std::vector<std::string> errors;  // ERE frames received, as text
  std::string error;                // the last thing that went wrong, for the beliefs
  std::uint64_t start_us = 0;
  int fai_sent = 0;
  // Updates since the first attitude, and those at which it was healthy.
  int ticks_since_attitude = 0, healthy_ticks = 0;

  // Intents (topconf drive). Angles and rates: yaw and pitch (roll is
  // self-stabilised, never commanded: SkyDroid header comment).
  void rate(double y, double p, double /*roll*/, bool /*earth*/) {
    idle = false, rate_mode = true, yaw_rate = y, pitch_rate = p;
    guard_yaw_.reset(), guard_pitch_.reset();
  }
  void angle(double y, double p, double /*roll*/, bool /*earth*/) {
    idle = false, rate_mode = false, target_yaw = y, target_pitch = p;
  }
  void stop() { idle = false, rate_mode = true, yaw_rate = pitch_rate = 0; }
  // RETRACT/NEUTRAL: PTZ 05, and the loop holds the centre.
  void centre() {
    now_.push_back(frame(top::Header::fixed, 'G', 'w', "PTZ", "05"));
    angle(0, 0, 0, false);
  }
  void photo() { camera_now('D', "CAP", "01"); }
  void record(bool on) { camera_now('D', "REC", on ? "01" : "00"); }
  void zoom(int r) {  // one step in (0A) or out (0B); no stop exists
    if (r != 0) camera_now('M', "DZM", r > 0 ? "0A" : "0B");
  }
  // A new device in place (topconf drive --persistent).
  void forget() { version.clear(), model.clear(), sd_present.reset(), error.clear(); }
  // Asked again at their steps of the round robin (VER 0, MOD 3).
  void ask_identity() { version.clear(), model.clear(); }
  void set_clock(const drive::Utc& u, std::uint64_t now_us) {
    clock_.set(drive::to_tm(u), now_us);
    now_.push_back(frame(top::Header::variable, 'D', 'w', "TIM", time_data(now_us)));
  }
  drive::Beliefs beliefs(std::uint64_t now_us) const {
    drive::Beliefs b;
    if (!attitude.empty())
      b.attitude = {attitude.back().roll, attitude.back().pitch, attitude.back().yaw};
    b.healthy = healthy(now_us);
    if (!version.empty()) b.version = version;
    if (model.find_first_not_of('0') != std::string::npos)
      b.model = model;
    else if (!model.empty())
      b.error = "the model name is the factory placeholder " + model;
    if (!error.empty()) b.error = error;
    return b;
  }

  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    if (start_us == 0) start_us = now_us;
    if (!attitude.empty()) {
      ++ticks_since_attitude;
      if (healthy(now_us)) ++healthy_ticks;
    }
    const std::uint64_t t = now_us - start_us;
    out.insert(out.end(), now_.begin(), now_.end());
    now_.clear();
    if (!mode_sent_) {
      out.push_back(frame(top::Header::fixed, 'G', 'w', "PTZ", "06"));  // follow
      mode_sent_ = true;
    }
    if (!idle) rates(now_us, out);
    if (now_us >= next_10hz_) {
      next_10hz_ = now_us + 100000;
      out.push_back(frame(top::Header::variable, 'G', 'w', "FAI", "00000000000000"));
      ++fai_sent;
      step_ = (step_ + 1) % 10;
      round_robin(now_us, out);
    }
    for (Timed& c : camera)
      if (!c.sent && t >= c.at_us) {
        out.push_back(frame(top::Header::fixed, c.dst, 'w', c.ident, c.data));
        c.sent = true;
      }
    return now_us + 20000;  // AP_Mount's 50 Hz update
  }

  void on_frame(const top::Frame& f, std::uint64_t now_us) override {
    if (!f.ok()) return;
    const std::string_view id = f.ident_view();
    const std::string_view d = f.data();
    if (id == "ERE") {
      errors.emplace_back(f.raw);
    } else if (id == "GAC" && d.size() >= 12) {
      int v[3];
      for (int i = 0; i < 3; ++i) {
        const auto x = hex16(d.substr(static_cast<std::size_t>(i) * 4, 4));
        if (!x) return;
        v[i] = *x;
      }
      double yaw = v[0] / 100.0;
      while (yaw > 180) yaw -= 360;
      while (yaw < -180) yaw += 360;
      attitude.push_back({now_us, yaw, v[1] / 100.0, v[2] / 100.0});
    } else if (id == "REC" && d.size() >= 2) {
      recording.push_back(d[1] == '1');
    } else if (id == "SDC" && d.size() >= 10) {
      sd_present = d.substr(0, 10) != "0000000000";
    } else if (id == "VER" && !d.empty() && d[0] == 'V') {
      // gimbal_version_analyse(): "V" then numbers between dots.
      version = drive::parse_version(d.substr(1), bugs.has(drive::Bug::strict_version)).text();
    } else if (id == "MOD" && !d.empty()) {
      // The whole name (the PR's driver keeps 7 chars: a longer one is cut).
      model = std::string(d.substr(0, std::min<std::size_t>(d.size(), 31)));
    }
  }

  // Healthy: a full GAC within the last second.
  bool healthy(std::uint64_t now_us) const {
    return !attitude.empty() && now_us - attitude.back().t_us <= 1000000;
  }

 private:
  void round_robin(std::uint64_t now_us, std::vector<std::string>& out) {
    switch (step_) {
      case 0:
        if (version.empty()) out.push_back(frame(top::Header::fixed, 'D', 'r', "VER", "00"));
        break;
      case 1:
        out.push_back(frame(top::Header::variable, 'D', 'w', "TIM", time_data(now_us)));
        break;
      case 2:
        // GAA every second, for a camera that reboots on its own; only
        // until the first GAC with no-reenable-after-reboot.
        if (!bugs.has(drive::Bug::no_reenable_after_reboot) || attitude.empty())
          out.push_back(frame(top::Header::fixed, 'G', 'w', "GAA", "32"));
        break;
      case 3:
        if (model.empty()) out.push_back(frame(top::Header::fixed, 'D', 'r', "MOD", "00"));
        break;
      case 4:
        out.push_back(frame(top::Header::fixed, 'D', 'r', "SDC", "00"));
        break;
      case 6:
        out.push_back(frame(top::Header::fixed, 'G', 'w', "FAE", "01"));
        break;
      default:
        break;
    }
  }
  void camera_now(char dst, std::string_view ident, std::string_view data) {
    if (sd_present == false && ident != "DZM") {
      error = "SD card absent: photo and video refused";
      return;
    }
    now_.push_back(frame(top::Header::fixed, dst, 'w', ident, data));
  }

  static std::optional<int> hex16(std::string_view s) {
    unsigned v = 0;
    for (char c : s) {
      const int x = top::hex_value(c);
      if (x < 0) return std::nullopt;
      v = v * 16 + static_cast<unsigned>(x);
    }
    return static_cast<int>(static_cast<std::int16_t>(static_cast<std::uint16_t>(v)));
  }

  static std::string byte_hex(int v) {
    char b[4];
    std::snprintf(b, sizeof b, "%02X", static_cast<unsigned>(static_cast<std::uint8_t>(v)));
    return b;
  }

  // A rate in deg/s as the signed LSB count at 0.5 deg/s, clamped to +-127.
  static int lsb(double rate) {
    return static_cast<int>(std::clamp(std::lround(rate / 0.5), -127L, 127L));
  }

  // The angle loop's rate for an error in deg: kP 1, +-63.5 deg/s, dead zone.
  static double loop_rate(double error) {
    if (std::fabs(error) < 0.05) return 0;
    return std::clamp(error * 1.0, -63.5, 63.5);
  }

  // GSY and GSP: from the rates, or the angle loop on the GAC attitude, while
  // the attitude is fresh (a GAC within 1 s; with rates-on-stale-attitude,
  // any GAC ever); otherwise zero. A zero pair is sent three times, then
  // nothing until a rate is due (none after a rate intent with
  // no-stop-after-last-rate).
  void rates(std::uint64_t now_us, std::vector<std::string>& out) {
    double y = 0, p = 0;
    const bool fresh =
        bugs.has(drive::Bug::rates_on_stale_attitude) ? !attitude.empty() : healthy(now_us);
    if (fresh) {
      const Attitude& a = attitude.back();
      if (rate_mode) {
        y = yaw_rate, p = pitch_rate;
      } else {
        double ey = target_yaw - a.yaw;
        while (ey > 180) ey -= 360;
        while (ey < -180) ey += 360;
        y = loop_rate(ey), p = loop_rate(target_pitch - a.pitch);
      }
      if (guard && !guard_yaw_.allow(y, a.yaw))
        y = 0, error = "yaw turns against its rate: stopped";
      if (guard && !guard_pitch_.allow(p, a.pitch))
        p = 0, error = "pitch turns against its rate: stopped";
    }
    const int gsy = -lsb(y);  // +GSY turns yaw left
    const int gsp = bugs.has(drive::Bug::pitch_rate_sign) ? -lsb(p) : lsb(p);
    if (gsy == 0 && gsp == 0) {
      if (zeros_ >= 3 || (rate_mode && bugs.has(drive::Bug::no_stop_after_last_rate))) return;
      ++zeros_;
    } else {
      zeros_ = 0;
    }
    out.push_back(frame(top::Header::fixed, 'G', 'w', "GSY", byte_hex(gsy)));
    out.push_back(frame(top::Header::fixed, 'G', 'w', "GSP", byte_hex(gsp)));
  }

  // TIM's data as the driver writes it from its UTC clock (hhmmss.ccDDMMYY,
  // 15 chars). The month 1-based; with month-zero-based 0-based, unconverted,
  // as the driver sends it (review of ArduPilot PR #34155;
  // docs/sources/ardupilot.md section 2.2, "TIM (month bug)").
  std::string time_data(std::uint64_t now_us) const {
    const std::tm u = clock_.now(now_us);
    const int month = u.tm_mon + (bugs.has(drive::Bug::month_zero_based) ? 0 : 1);
    char b[32];
    std::snprintf(b, sizeof b, "%02d%02d%02d.00%02d%02d%02d", u.tm_hour, u.tm_min, u.tm_sec,
                  u.tm_mday, month, u.tm_year % 100);
    return b;
  }

  std::string frame(top::Header h, char dst, char control, std::string_view ident,
                    std::string_view data) const {
    return top::build_frame(
        {.header = h, .src = client, .dst = dst, .control = control, .ident = ident, .data = data});
  }

  bool mode_sent_ = false;
  std::uint64_t next_10hz_ = 0;
  int step_ = 0;
  int zeros_ = 0;
  std::vector<std::string> now_;  // intents' frames, sent at the next update
  drive::RunawayGuard guard_yaw_, guard_pitch_;
  drive::Clock clock_;
};
