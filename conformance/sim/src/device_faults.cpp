// The device faults of topsim --fault: what a faulty gimbal does that
// topdump names as a field diagnosis (docs/DIAGNOSES.md). The identifiers
// they name are checked against protocol/'s tables: a stream's push
// (top::streams), a motion command (top::motion_of).
#include "device_faults.hpp"

#include <cstdlib>

#include "top/device.hpp"
#include "top/motion.hpp"

namespace topsim::detail {
namespace {

// Whether `id` is what a stream of either dialect pushes (GAC, GIC, GIA, OFT).
bool is_push(std::string_view id) {
  for (const top::StreamSpec& s : top::streams())
    if (s.sender == top::Sender::device && s.push == id) return true;
  return false;
}

// Whether `id` moves the gimbal in either dialect (angle, rate or PTZ).
bool is_motion(std::string_view id) {
  for (const top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek})
    if (const top::MotionSpec* m = top::motion_of(d, id))
      if (m->kind == top::MotionKind::angle || m->kind == top::MotionKind::rate ||
          m->kind == top::MotionKind::ptz)
        return true;
  return false;
}

// Seconds (decimals allowed) as microseconds; false unless 0 to 3600.
bool seconds(std::string_view v, std::uint64_t& us) {
  if (v.empty() || v.front() == '+' || v.front() == '-') return false;
  const std::string s(v);
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !(x >= 0 && x <= 3600)) return false;
  us = static_cast<std::uint64_t>(x * 1e6 + 0.5);
  return true;
}

}  // namespace

Parsed parse_device_fault(std::string_view name, bool has_value, std::string_view value,
                          DeviceFaults& out, std::string& why) {
  auto bad = [&](std::string_view w) {
    why = std::string(w);
    return Parsed::bad;
  };
  if (name == "stall") {
    // IDENT@T+S: T seconds after the stream was switched on, for S seconds.
    const std::size_t at = value.find('@'), plus = value.find('+', at);
    DeviceFaults::Mute m;
    std::uint64_t from = 0, len = 0;
    if (at == std::string_view::npos || plus == std::string_view::npos ||
        !seconds(value.substr(at + 1, plus - at - 1), from) ||
        !seconds(value.substr(plus + 1), len) || len == 0)
      return bad("stall needs IDENT@T+S: a push stream, seconds after it started, seconds (> 0)");
    m.ident = std::string(value.substr(0, at));
    if (!is_push(m.ident))
      return bad("stall: '" + m.ident + "' is no push stream (GAC GIC GIA OFT)");
    m.from_us = from;
    m.until_us = from + len;
    out.mutes.push_back(std::move(m));
    return Parsed::ok;
  }
  if (name == "no-stream") {
    if (!is_push(value)) return bad("no-stream needs a push stream's identifier (GAC GIC GIA OFT)");
    out.mutes.push_back(DeviceFaults::Mute{std::string(value), 0, DeviceFaults::kForever});
    return Parsed::ok;
  }
  if (name == "ignore-motion") {
    for (std::size_t start = 0;;) {
      const std::size_t plus = value.find('+', start);
      const std::string_view id = value.substr(
          start, plus == std::string_view::npos ? std::string_view::npos : plus - start);
      if (!is_motion(id))
        return bad("ignore-motion needs motion commands (GAY, GSP, YPR, PTZ...), joined by +");
      out.ignore_motion.emplace_back(id);
      if (plus == std::string_view::npos) break;
      start = plus + 1;
    }
    return Parsed::ok;
  }
  if (name == "invert") {
    const std::size_t colon = value.find(':');
    const std::string_view axis = value.substr(0, colon);
    const std::string_view kind =
        colon == std::string_view::npos ? std::string_view{} : value.substr(colon + 1);
    const int i = axis == "yaw" ? 0 : axis == "pitch" ? 1 : axis == "roll" ? 2 : -1;
    const std::uint8_t bits = kind.empty() && colon == std::string_view::npos
                                  ? DeviceFaults::kInvertAngle | DeviceFaults::kInvertRate
                              : kind == "angle" ? DeviceFaults::kInvertAngle
                              : kind == "rate"  ? DeviceFaults::kInvertRate
                                                : 0;
    if (i < 0 || bits == 0) return bad("invert needs yaw, pitch or roll, then :angle or :rate");
    out.invert[i] |= bits;
    return Parsed::ok;
  }
  if (name == "placeholder-identity" || name == "refuse-tracking") {
    if (has_value) return bad("takes no value");
    (name == "refuse-tracking" ? out.refuse_tracking : out.placeholder_identity) = true;
    return Parsed::ok;
  }
  if (name == "stop") {
    // IDENT@T: the device switches the stream off T seconds after it started.
    const std::size_t at = value.find('@');
    std::uint64_t from = 0;
    if (at == std::string_view::npos || !seconds(value.substr(at + 1), from))
      return bad("stop needs IDENT@T: a push stream, seconds after it started");
    DeviceFaults::Mute m{std::string(value.substr(0, at)), from, DeviceFaults::kForever};
    if (!is_push(m.ident))
      return bad("stop: '" + m.ident + "' is no push stream (GAC GIC GIA OFT)");
    if (out.stops.size() >= 32) return bad("stop: at most 32");
    out.stops.push_back(std::move(m));
    return Parsed::ok;
  }
  if (name == "ere") {
    if (value.size() != 3) return bad("ere needs a three-character identifier");
    out.ere.emplace_back(value);
    return Parsed::ok;
  }
  if (name == "range-form") {
    if (value != "short") return bad("range-form needs short");
    out.range_short = true;
    return Parsed::ok;
  }
  if (name == "clock") {
    if (value != "month-early") return bad("clock needs month-early");
    out.clock_month_early = true;
    return Parsed::ok;
  }
  return Parsed::not_mine;
}

}  // namespace topsim::detail
