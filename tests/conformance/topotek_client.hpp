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
//
// For topconf drive (issue 50) it takes the drive contract's intents (the
// methods under "Intents"), says what it believes (beliefs()), and can be
// switched to the known bugs of drive_client/drive_api.hpp (`bugs`). Without
// a bug it is what a good driver does where the upstream driver is known to
// be wrong: GIA read only with its 12 data chars, the LRF range by its
// length, no rate sent on an attitude older than 1 s, a version without dots
// read as the driver documents it, and a runaway guard on its rates.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "drive_client/drive_api.hpp"
#include "drive_client/intents.hpp"
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
  // No target at all until the first motion intent (topkit_drive_client);
  // the upstream driver sends its targets from the start.
  bool idle = false;
  // The runaway guard on rates (drive::RunawayGuard): on in topconf
  // drive's clients; off where a test watches a device turn the wrong way.
  bool guard = false;
  drive::Bugs bugs;

  // What the driver learnt.
  struct Attitude {
    std::uint64_t t_us;
    double yaw, pitch, roll;  // deg, pitch up positive (the wire's negated)
  };
  std::vector<Attitude> attitude;  // from GIA frames (12 data chars, or any with echo-as-attitude)
  int short_gia = 0;               // GIA frames without 12 data chars (the enable's echo): the
                                   // driver, which checks no length, would read garbage from them
  bool version_parsed = false;
  int version[3] = {0, 0, 0};
  int version_parts = 0;  // how many of version[] the reply gave
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
  std::string error;  // the last thing that went wrong, for the beliefs

  // Commands as the driver's API gives them; sent at the next tick.
  void record(bool on) {
    if (refused_without_card()) return;
    pending_.push_back(fixed('D', 'w', "REC", on ? 1 : 0));
  }
  // A tracking point at the image centre (section 1.2: a 60-pixel box).
  void track_centre() { track_point(0.5, 0.5); }
  void cancel_tracking() { pending_.push_back(fixed('D', 'w', "TRC", track_state == '2' ? 1 : 0)); }
  // set_rangefinder_enable(): 03 continuous measurement, 00 stop, to M.
  void rangefinder(bool on) { pending_.push_back(fixed('M', 'w', "LRF", on ? 3 : 0)); }
  // The range intent: one measurement (LRF 02, Topotek 5.9 note 2).
  void measure_range() { pending_.push_back(fixed('M', 'w', "LRF", 2)); }

  // Intents (topconf drive): the driver API's calls they stand for.
  void rate(double y, double p, double r, bool /*earth*/) {
    moving(), rate_mode = true, yaw_rate = y, pitch_rate = p, roll_rate = r;
    guard_yaw_.reset(), guard_pitch_.reset();
  }
  void angle(double y, double p, double r, bool /*earth: always body, see targets()*/) {
    moving(), rate_mode = false, yaw = y, pitch = p, roll = r;
  }
  void stop() { moving(), rate_mode = true, yaw_rate = pitch_rate = roll_rate = 0; }
  void centre() { angle(0, 0, 0, false); }
  void photo() {
    if (!refused_without_card()) pending_.push_back(fixed('D', 'w', "CAP", 1));
  }
  // set_zoom(RATE): 02 in, 01 out, 00 stop (sent again at the next tick).
  void zoom(int r) {
    pending_.push_back(fixed('M', 'w', "ZMC", r > 0 ? 2 : r < 0 ? 1 : 0));
    zoom_stop_again_ = r == 0;
  }
  // set_tracking(): a point as a 60-pixel box, a box by its corners, both on
  // the +-1000 grid of a 1920x1080 image; TRC 02 first when stopped.
  void track_point(double x, double y) {
    track_at(grid_x(x * 1920), grid_y(y * 1080), static_cast<int>(60 / 0.96),
             static_cast<int>(60 / 0.54), 0x0009);
  }
  void track_box(double x, double y, double w, double h) {
    if (w <= 0 || h <= 0) {
      error = "track_box of no area refused";
      return;
    }
    track_at(grid_x((x + w / 2) * 1920), grid_y((y + h / 2) * 1080),
             static_cast<int>(w * 1920 / 0.96), static_cast<int>(h * 1080 / 0.54), 0x0001);
  }
  void track_stop() { cancel_tracking(); }
  // Asked again at their steps of the round robin (VSN 0, PA2 8), as the
  // driver asks them until answered: not all at once (a slow reply on a
  // serial line holds back what follows it).
  void ask_identity() { version_parsed = false, model_name.clear(); }
  // Sets the camera clock now, and keeps the time for the UTC frames after.
  void set_clock(const drive::Utc& u, std::uint64_t now_us) {
    clock_.set(drive::to_tm(u), now_us);
    pending_.push_back(utc(now_us));
  }

  // A new device in place (topconf drive --persistent): its identity,
  // tracking state and range are not known yet.
  void forget() {
    version_parsed = false, version_parts = 0, model_name.clear();
    track_states.clear(), track_state = '0', tracking = false;
    distance_m = -1, error.clear();
  }

  // Healthy: a GIA within the last second (healthy(), 1000 ms).
  bool healthy(std::uint64_t now_us) const {
    return !attitude.empty() && now_us - attitude.back().t_us < 1000000;
  }
  drive::Beliefs beliefs(std::uint64_t now_us) const {
    drive::Beliefs b;
    if (!attitude.empty())
      b.attitude = {attitude.back().roll, attitude.back().pitch, attitude.back().yaw};
    b.healthy = healthy(now_us);
    if (version_parsed) b.version = version_text();
    // What it parsed; the factory placeholder (PR #27568) is no name: unknown.
    if (model_name.find_first_not_of('0') != std::string::npos)
      b.model = model_name;
    else if (!model_name.empty())
      b.error = "the model name is the factory placeholder " + model_name;
    static constexpr const char* kStates[] = {"off", "searching", "tracking", "lost", "refused"};
    if (!track_states.empty() && track_state >= '0' && track_state <= '4')
      b.tracking = kStates[track_state - '0'];
    if (distance_m >= 0) b.range_m = distance_m;
    if (!error.empty()) b.error = error;
    return b;
  }

  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    out.insert(out.end(), pending_.begin(), pending_.end());
    pending_.clear();
    if (zoom_stop_again_ && !sent_zoom_stop_) {
      out.push_back(fixed('M', 'w', "ZMC", 0));
      sent_zoom_stop_ = true;
    } else if (!zoom_stop_again_) {
      sent_zoom_stop_ = false;
    }
    if (utc_due_) {
      utc_due_ = false;
      if (utc_sent < 7) out.push_back(utc(now_us)), ++utc_sent;
    }
    position(out);
    // The 1 Hz round robin as the driver's profile gives it
    // (conformance/drivers: its steps, identifiers and the ones sent until
    // answered), one step a tick.
    const int step = static_cast<int>(++step_ % 10);
    for (const drivers::Sent& q : profile().sends)
      if (q.slot == step && !(q.until_answered && answered(q.ident)) &&
          !(q.ident == "GIA" && bugs.has(drive::Bug::no_reenable_after_reboot) &&
            !attitude.empty()))
        out.push_back(frame(top::Header::fixed, q.dst, q.control, q.ident, q.data));
    if (!tracking && !idle) targets(now_us, out);
    return now_us + std::uint64_t{profile().tick_ms} * 1000;
  }
  static const drivers::Profile& profile() {
    static const drivers::Profile* p = drivers::find_profile("ardupilot-topotek");
    return *p;
  }

  void on_frame(const top::Frame& f, std::uint64_t now_us) override {
    if (!f.ok()) return;
    ++frames;
    // The driver's receive buffer: each frame over the start of the last.
    buffer_.replace(0, std::min(f.raw.size(), buffer_.size()), f.raw, 0,
                    std::min(f.raw.size(), buffer_.size()));
    const std::string_view id = f.ident_view(), d = f.data();
    if (id == "ERE") ++ere;
    if (id == "OFT") ++oft;
    if (id == "GIA") {
      gia(d, now_us);
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
      distance_m = bugs.has(drive::Bug::range_fixed_offsets) ? distance(f.raw) : range_of(d);
    }
  }

 private:
  std::uint64_t step_ = 0;
  // What the driver stops asking once parsed (Sent::until_answered).
  bool answered(std::string_view ident) const {
    return (ident == "VSN" && version_parsed) || (ident == "PA2" && !model_name.empty());
  }
  int stops_ = 0;
  bool utc_due_ = false, zoom_stop_again_ = false, sent_zoom_stop_ = false;
  std::vector<std::string> pending_;
  std::string buffer_ = std::string(64, '\0');  // the driver's _msg_buff
  drive::RunawayGuard guard_yaw_, guard_pitch_;
  drive::Clock clock_;

  void moving() { idle = false; }
  // record_video(), take_picture(): refused while the card is known bad.
  bool refused_without_card() {
    if (!sd_parsed || sd_ok) return false;
    error = "SD card error: photo and video refused";
    return true;
  }
  static int grid_x(double px) { return static_cast<int>((px - 960) / 0.96); }
  static int grid_y(double py) { return static_cast<int>((py - 540) / 0.54); }
  void track_at(int x, int y, int w, int h, int mode) {
    if (track_state == '0') pending_.push_back(fixed('D', 'w', "TRC", 2));
    pending_.push_back(loc(x, y, w, h, mode));
  }

  // gimbal_angle_analyse(): yaw, pitch (negated), roll from data chars 0-11.
  // A good driver takes a GIA of 12 data chars only; echo-as-attitude reads
  // them at buffer offsets 10-21 whatever the frame's length (a non-hex char
  // drops it, as @ 05ad8d27 does).
  void gia(std::string_view d, std::uint64_t now_us) {
    std::string_view at = d;
    if (d.size() != 12) {
      ++short_gia;
      if (!bugs.has(drive::Bug::echo_as_attitude)) return;
      at = std::string_view(buffer_).substr(10, 12);
      for (char c : at)
        if (top::hex_value(c) < 0) return;
    }
    Attitude a{now_us, s16(at.substr(0, 4)) * 0.01, -s16(at.substr(4, 4)) * 0.01,
               s16(at.substr(8, 4)) * 0.01};
    while (a.yaw > 180) a.yaw -= 360;
    while (a.yaw < -180) a.yaw += 360;
    attitude.push_back(a);
  }

  static int s16(std::string_view h) {
    int v = 0;
    for (char c : h) v = v * 16 + std::max(0, top::hex_value(c));
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(v));
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
  // The source address: the link's (U on a UART, P on a network: PR
  // #33803), or U whatever the link with uart-address-on-network.
  char source() const { return bugs.has(drive::Bug::uart_address_on_network) ? 'U' : client; }
  std::string frame(top::Header h, char dst, char ctl, std::string_view id,
                    std::string_view data) const {
    return top::build_frame(
        {.header = h, .src = source(), .dst = dst, .control = ctl, .ident = id, .data = data});
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
  // UTC HHMMSSDDMMYY, the month 1-based (send_time_to_gimbal: month + 1),
  // 0-based with month-zero-based. `month0` is 0-11.
  std::string utc_frame(int h, int m, int s, int day, int month0, int year) const {
    char b[80];
    const int month = month0 + (bugs.has(drive::Bug::month_zero_based) ? 0 : 1);
    std::snprintf(b, sizeof b, "%02d%02d%02d%02d%02d%02d", h, m, s, day, month, year % 100);
    return var('D', "UTC", b);
  }
  std::string utc(std::uint64_t now_us) const {
    const std::tm tm = clock_.now(now_us);
    return utc_frame(tm.tm_hour, tm.tm_min, tm.tm_sec, tm.tm_mday, tm.tm_mon, tm.tm_year + 1900);
  }
  // A fixed position: 35.335343 N, 138.727 E, 123.4 m, heading 45.
  void position(std::vector<std::string>& out) const {
    out.push_back(var('D', "LAT", "N3520.1206"));
    out.push_back(var('D', "LON", "E13843.6200"));
    out.push_back(var('D', "ALT", "000123.4"));
    out.push_back(var('D', "AZI", "045.0"));
  }
  void targets(std::uint64_t now_us, std::vector<std::string>& out) {
    if (!rate_mode) {
      stops_ = 0;
      // Yaw body frame, pitch negated (down positive on the wire), speed 99.
      out.push_back(var('G', "GAY", hex4(yaw * 100) + "63"));
      out.push_back(var('G', "GIP", hex4(-pitch * 100) + "63"));
      out.push_back(var('G', "GIR", hex4(roll * 100) + "63"));
      return;
    }
    // A good driver sends no rate on an attitude older than 1 s (it stops
    // instead); rates-on-stale-attitude only waits for a first attitude.
    const bool fresh =
        bugs.has(drive::Bug::rates_on_stale_attitude) ? !attitude.empty() : healthy(now_us);
    std::optional<double> at_yaw, at_pitch;
    if (!attitude.empty()) at_yaw = attitude.back().yaw, at_pitch = attitude.back().pitch;
    double yr = fresh ? yaw_rate : 0, pr = fresh ? pitch_rate : 0;
    const double rr = fresh ? roll_rate : 0;
    if (guard && !guard_yaw_.allow(yr, at_yaw))
      yr = 0, error = "yaw turns against its rate: stopped";
    if (guard && !guard_pitch_.allow(pr, at_pitch))
      pr = 0, error = "pitch turns against its rate: stopped";
    // deg/s x 1.220740379, +-99, pitch negated (PR #29002; not with pitch-rate-sign).
    auto ypr_byte = [](double r) {
      return hex2(std::lround(std::fmax(-99, std::fmin(99, r * 1.220740379))));
    };
    const std::string ypr =
        ypr_byte(yr) + ypr_byte(bugs.has(drive::Bug::pitch_rate_sign) ? pr : -pr) + ypr_byte(rr);
    if (ypr == "000000") {
      // PTZ 00 three times when the rates go to zero (send_target_rates);
      // none with no-stop-after-last-rate.
      if (stops_ < 3 && !bugs.has(drive::Bug::no_stop_after_last_rate))
        out.push_back(fixed('G', 'w', "PTZ", 0));
      ++stops_;
      return;
    }
    stops_ = 0;
    out.push_back(var('G', "YPR", ypr));
  }
  // The driver's buffer holds the frame from '#': data starts at byte 10.
  // ERR in data chars 0-2 is no range; otherwise the digits of "12345.6" are
  // read at chars 0-4 and 6, char 5 skipped, whatever the length char says
  // (each as a hex nibble, as the driver converts them): range-fixed-offsets.
  static double distance(std::string_view raw) {
    auto at = [&](std::size_t i) { return 10 + i < raw.size() ? raw[10 + i] : '\0'; };
    if (at(0) == 'E' && at(1) == 'R' && at(2) == 'R') return -1;
    auto nib = [&](std::size_t i) { return std::max(0, top::hex_value(at(i))); };
    return nib(0) * 10000.0 + nib(1) * 1000.0 + nib(2) * 100.0 + nib(3) * 10.0 + nib(4) +
           nib(6) * 0.1;
  }
  // A good driver reads the range as the decimal number the data is, of
  // any length (ERR: none; anything else keeps the last range).
  double range_of(std::string_view d) const {
    if (d.substr(0, 3) == "ERR") return -1;
    double v = 0, scale = 0;
    bool digits = false;
    for (char c : d) {
      if (c == '.' && scale == 0) {
        scale = 1;
      } else if (c >= '0' && c <= '9') {
        digits = true;
        if (scale > 0)
          scale /= 10, v += (c - '0') * scale;
        else
          v = v * 10 + (c - '0');
      } else {
        return distance_m;
      }
    }
    return digits ? v : distance_m;
  }
  std::string version_text() const {
    drive::Version v;
    std::copy(version, version + 3, v.parts);
    v.n = version_parts;
    return v.text();
  }
  void parse_version(std::string_view d) {
    const drive::Version v = drive::parse_version(d, bugs.has(drive::Bug::strict_version));
    if (v.n == 0) return;  // unknown: asked again at the next round
    std::copy(v.parts, v.parts + 3, version);
    version_parts = v.n;
    version_parsed = true;
  }
};
