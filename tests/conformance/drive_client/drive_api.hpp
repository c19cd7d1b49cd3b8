// What the driver-like clients (topotek_client.hpp, driver_skydroid.hpp)
// share for `topconf drive` (issue 50, docs/DRIVE.md): the known driver
// bugs they can be switched to, what they believe (the "beliefs" of the
// drive contract, printed as JSON Lines by topkit_drive_client), and the
// runaway guard a good driver keeps on its rate commands.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace drive {

// One switch per known real driver bug (issue 50 item 5). Each names the
// case of `topconf drive` it must fail (docs/DRIVE.md), and its source.
enum class Bug : std::uint8_t {
  pitch_rate_sign,           // 2.1
  uart_address_on_network,   // 6.4
  strict_version,            // 3.2
  echo_as_attitude,          // 6.5
  range_fixed_offsets,       // 8.3
  month_zero_based,          // 9.1
  no_stop_after_last_rate,   // 2.4
  no_reenable_after_reboot,  // 1.4
  rates_on_stale_attitude,   // 2.5
};
inline constexpr std::size_t kBugs = 9;

struct BugInfo {
  Bug bug;
  std::string_view name;   // --bug NAME
  std::string_view cases;  // the case(s) of topconf drive it fails
  bool topotek, skydroid;  // the drivers it is a bug of
  std::string_view what;   // what the client does, and the source
};

inline const std::array<BugInfo, kBugs>& bug_table() {
  static const std::array<BugInfo, kBugs> t = {{
      {Bug::pitch_rate_sign, "pitch-rate-sign", "2.1", true, true,
       "pitch rates sent with the wrong sign: AP_Mount_Topotek before ArduPilot PR #29002 sent "
       "YPR's pitch un-negated (Topotek's wire is down-positive); on SkyDroid GSP negated"},
      {Bug::uart_address_on_network, "uart-address-on-network", "6.4", true, false,
       "source address U (UART) on a UDP/TCP link, where a Topotek camera answers only P: "
       "AP_Mount_Topotek before ArduPilot PR #33803"},
      {Bug::strict_version, "strict-version", "3.2", true, true,
       "a version parser that knows only dotted numbers (\"%u.%u.%u\"): a version without dots "
       "(\"123\", the other form AP_Mount_Topotek documents since ArduPilot PR #27568) reads as "
       "major 123"},
      {Bug::echo_as_attitude, "echo-as-attitude", "6.5 1.1", true, false,
       "GIA parsed with no length check, at fixed offsets of a buffer that keeps the bytes of "
       "earlier frames: AP_Mount_Topotek.cpp @ 05ad8d27 gimbal_angle_analyse() reads "
       "hex_chars_to_uint32(&_msg_buff[10], 4, yaw_raw), [14] pitch, [18] roll, whatever the "
       "length char says, so the 2-char echo of its own GIA 01 is an attitude"},
      {Bug::range_fixed_offsets, "range-fixed-offsets", "8.3", true, false,
       "the LRF range read at data chars 0-4 and 6 whatever the reply's length: "
       "AP_Mount_Topotek.cpp @ 05ad8d27 gimbal_dist_info_analyse()"},
      {Bug::month_zero_based, "month-zero-based", "9.1", true, true,
       "the clock's month sent 0-based: AP_Mount_SkyDroid (ArduPilot PR #34155 @ 241167dc, "
       "send_time_sync, review of head a60aa188: \"every timestamp is one month early\")"},
      {Bug::no_stop_after_last_rate, "no-stop-after-last-rate", "2.4", true, true,
       "no zero rate after the last rate command: the axis is left to the device's speed hold "
       "(QGroundControl #13580, an axis left spinning; ArduPilot PR #30872)"},
      {Bug::no_reenable_after_reboot, "no-reenable-after-reboot", "1.4 1.3", true, true,
       "the attitude stream switched on until it first came, never again: a camera that reboots "
       "on its own comes back with its stream off (AP_Mount_SkyDroid re-sends GAA every second "
       "for this, AP_Mount_Topotek GIA 01)"},
      {Bug::rates_on_stale_attitude, "rates-on-stale-attitude", "2.5", true, true,
       "rate commands kept on an attitude older than 1 s: AP_Mount_Topotek sends YPR whatever "
       "its health; the PR #34155 review (\"angle loop uses stale attitude on feedback loss\")"},
  }};
  return t;
}

inline const BugInfo& info(Bug b) { return bug_table()[static_cast<std::size_t>(b)]; }
inline std::optional<Bug> parse_bug(std::string_view name) {
  for (const BugInfo& i : bug_table())
    if (i.name == name) return i.bug;
  return std::nullopt;
}

class Bugs {
 public:
  bool has(Bug b) const noexcept { return (bits_ >> static_cast<unsigned>(b)) & 1U; }
  Bugs& set(Bug b) noexcept {
    bits_ |= 1U << static_cast<unsigned>(b);
    return *this;
  }
  bool any() const noexcept { return bits_ != 0; }

 private:
  std::uint32_t bits_ = 0;
};

// What the driver believes, as the drive contract's beliefs line: any
// subset of the keys. Tracking: off, searching, tracking, lost, refused.
struct Beliefs {
  struct Attitude {
    double roll, pitch, yaw;  // deg, pitch up positive, yaw right positive
  };
  std::optional<Attitude> attitude;
  bool healthy = false;
  std::optional<std::string> version, model, tracking, error;
  std::optional<double> range_m;

  nlohmann::json to_json() const {
    nlohmann::json j;
    if (attitude)
      j["attitude"] = {
          {"roll", attitude->roll}, {"pitch", attitude->pitch}, {"yaw", attitude->yaw}};
    j["healthy"] = healthy;
    if (version) j["version"] = *version;
    if (model) j["model"] = *model;
    if (tracking) j["tracking"] = *tracking;
    if (range_m) j["range_m"] = *range_m;
    if (error) j["error"] = *error;
    return j;
  }
};

// A good driver's guard on an axis it turns with rate commands (case 2.2:
// "the commanded pitch never runs away to the limit"): when the attitude
// moves 3 deg or more against the rate it holds, the device turns the
// other way (a sign inverted), and the axis is given up (zero rate) with an
// error, instead of driving it on to its stop.
class RunawayGuard {
 public:
  static constexpr double kAgainstDeg = 3;
  bool tripped() const noexcept { return tripped_; }
  // A rate of `rate` deg/s is commanded while the axis stands at `angle`.
  // Returns false once tripped (the rate must not be sent).
  bool allow(double rate, std::optional<double> angle) {
    if (tripped_) return false;
    const int sign = rate > 0 ? 1 : rate < 0 ? -1 : 0;
    if (sign == 0 || !angle) {
      sign_ = 0;
      return true;
    }
    if (sign != sign_) {
      sign_ = sign;
      from_ = *angle;
    }
    if ((*angle - from_) * sign <= -kAgainstDeg) tripped_ = true;
    return !tripped_;
  }
  void reset() noexcept { tripped_ = false, sign_ = 0; }

 private:
  bool tripped_ = false;
  int sign_ = 0;
  double from_ = 0;
};

// A firmware version reply's numbers (at most three; n == 0: not a version).
// A good driver takes the decimal numbers between dots, the last one too,
// until a part that is not one ("1.6.26.R.D" is 1.6.26, "1.2.3" 1.2.3), or
// up to three digits without a dot as one number each ("123" is 1.2.3, the
// form AP_Mount_Topotek.cpp gimbal_version_analyse() documents since PR
// #27568; "1" is 1).
// `strict` (strict-version) reads dotted numbers only, as sscanf("%d.%d.%d")
// does: "123" is 123.
struct Version {
  int parts[3] = {0, 0, 0};
  int n = 0;
  std::string text() const {
    std::string s;
    for (int i = 0; i < n; ++i) s += (i ? "." : "") + std::to_string(parts[i]);
    return s;
  }
};
inline Version parse_version(std::string_view d, bool strict) {
  Version v;
  const auto digits = [](std::string_view p) {
    return !p.empty() && p.size() <= 4 &&
           std::all_of(p.begin(), p.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (strict) {
    const std::string s(d.substr(0, 32));
    v.n = std::sscanf(s.c_str(), "%d.%d.%d", &v.parts[0], &v.parts[1], &v.parts[2]) > 0 ? 3 : 0;
    return v;
  }
  if (d.find('.') == std::string_view::npos) {
    if (d.size() <= 3 && digits(d))
      for (v.n = 0; v.n < static_cast<int>(d.size()); ++v.n)
        v.parts[v.n] = d[static_cast<std::size_t>(v.n)] - '0';
    return v;
  }
  for (std::size_t i = 0; v.n < 3 && i <= d.size();) {
    const std::size_t e = std::min(d.find('.', i), d.size());
    if (!digits(d.substr(i, e - i))) break;
    v.parts[v.n++] = std::stoi(std::string(d.substr(i, e - i)));
    i = e + 1;
  }
  return v;
}

// The camera clock a driver sets: the system's UTC, or from a clock intent
// on, the intent's time and what has passed since.
class Clock {
 public:
  void set(const std::tm& utc, std::uint64_t now_us) {
    std::tm t = utc;
    base_ = timegm(&t);
    at_us_ = now_us;
  }
  std::tm now(std::uint64_t now_us) const {
    std::time_t t = std::time(nullptr);
    if (base_) t = *base_ + static_cast<std::time_t>((now_us - at_us_) / 1000000);
    std::tm tm{};
    gmtime_r(&t, &tm);
    return tm;
  }

 private:
  std::optional<std::time_t> base_;
  std::uint64_t at_us_ = 0;
};

}  // namespace drive
