// The device rules that conformance/ writes by hand, each in one place, so
// that the simulator, the runner, the fuzzer and the matrix generator ask
// the same function. Each is a stand-in for a protocol/ call to come (the
// lead's device-rule API): swap the body, keep the callers.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "top/top.hpp"

namespace topsim {

// The link a request arrived on. Topotek answers only when the request's
// source byte names that link: P for the network, U for the UART.
enum class Link : std::uint8_t { network, uart };

namespace rules {

// Link answering by source (field notes; the trait link_by_source): the
// client address a device of `d` answers on `link`. Topotek: P on the
// network, U on the UART; SkyDroid: U everywhere.
constexpr char client_address(top::Dialect d, Link link) noexcept {
  return d == top::Dialect::topotek && link == Link::network ? 'P' : 'U';
}

// Whether a device of `d` answers a request with source address `src` that
// arrived on `link` (SkyDroid answers every source).
constexpr bool answers_source(top::Dialect d, Link link, char src) noexcept {
  return d != top::Dialect::topotek || src == client_address(d, link);
}

// Rejecting findings: a request with one of these gets ERE (SkyDroid) or
// silence (Topotek), unless field evidence lifts it.
constexpr bool rejects(top::FindingCode c) noexcept {
  switch (c) {
    case top::FindingCode::unknown_ident:
    case top::FindingCode::unsupported_on_model:
    case top::FindingCode::unsupported_control:
    case top::FindingCode::data_length:
    case top::FindingCode::bad_field:
    case top::FindingCode::value_out_of_range:
      return true;
    default:
      return false;
  }
}
inline bool rejects(const top::Decoded& dec) noexcept {
  for (const auto& f : dec.findings)
    if (rejects(f.code)) return true;
  return false;
}

// The error reply (SkyDroid 2.3.2): #TP<dst><src>2wERE!!<cs>.
inline constexpr std::string_view kErrorIdent = "ERE";
inline constexpr std::string_view kErrorData = "!!";
// Whether a frame of identifier `ident` is the error reply.
constexpr bool is_error_reply(std::string_view ident) noexcept { return ident == kErrorIdent; }
// Whether a device of `d` answers a rejected request with ERE (Topotek is
// silent).
constexpr bool sends_error_reply(top::Dialect d) noexcept { return d == top::Dialect::skydroid; }
// The error reply from `device` to `client` (addresses already ordered).
inline std::string error_reply(char src, char dst) {
  top::BuildSpec spec;
  spec.header = top::Header::fixed;
  spec.src = src;
  spec.dst = dst;
  spec.control = 'w';
  spec.ident = kErrorIdent;
  spec.data = kErrorData;
  return top::build_frame(spec);
}

// Motion (SkyDroid 3.x): what a command does to the gimbal's axes.
enum class MotionKind : std::uint8_t { angle, rate };
struct Motion {
  std::string_view ident;
  MotionKind kind;
  int axis;                      // 0 yaw, 1 pitch, 2 roll; -1: both per the fields
  std::string_view value_field;  // angle commands: the target angle
  std::string_view speed_field;  // the speed (angle: toward the target)
};
// The axis a single-axis motion identifier names by its third letter (Y, P,
// R), or -1.
constexpr int axis_of(std::string_view ident) noexcept {
  if (ident.size() < 3) return -1;
  const char c = ident[2];
  return c == 'Y' ? 0 : c == 'P' ? 1 : c == 'R' ? 2 : -1;
}
inline constexpr Motion kMotions[] = {
    {"GAY", MotionKind::angle, axis_of("GAY"), "angle", "speed"},
    {"GAP", MotionKind::angle, axis_of("GAP"), "angle", "speed"},
    {"GAR", MotionKind::angle, axis_of("GAR"), "angle", "speed"},
    {"GAM", MotionKind::angle, 0, "yaw", "yaw_speed"},
    {"GAM", MotionKind::angle, 1, "pitch", "pitch_speed"},
    {"GSY", MotionKind::rate, axis_of("GSY"), "", "speed"},
    {"GSP", MotionKind::rate, axis_of("GSP"), "", "speed"},
    {"GSR", MotionKind::rate, axis_of("GSR"), "", "speed"},
    {"GSM", MotionKind::rate, 0, "", "yaw_speed"},
    {"GSM", MotionKind::rate, 1, "", "pitch_speed"},
};

// Timing. The line is quiet (a stream device decides on bytes it holds)
// after this long without a byte.
inline constexpr std::uint32_t kQuietLineMs = 20;
// A speed command holds for this long unless refreshed (field notes: the
// trait speed_refresh; motors stop when rate commands are not refreshed).
inline constexpr std::uint32_t kSpeedHoldMs = 1000;
// A stream's measured rate may differ from the one asked for by this
// fraction (the default matrices and the matrix loader's default).
inline constexpr double kStreamRateTolerance = 0.25;

}  // namespace rules
}  // namespace topsim
