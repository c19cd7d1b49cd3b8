// A motion command window as the motion track (motion_track.hpp) closes it:
// what was commanded on one axis from its first command to the next
// command of another value, and where the attitude was at its start and
// end. Angles are up and right positive, in the convention of the attitude
// the window is judged against (top::field_convention).
#pragma once

#include <cstdint>
#include <string_view>

#include "capture/sink.hpp"
#include "top/motion.hpp"

namespace topdump::diag {

// What every case of a window names: its command, its axis, where the
// commands came from, and the attitude it was read against.
struct WindowOf {
  const top::MotionSpec* spec = nullptr;
  int axis = 0;               // top::Axis
  int dir = 0;                // the direction the commands came from
  std::string_view attitude;  // the attitude's identifier ("GAC", "GIA")
};

struct Judged : WindowOf {
  std::uint64_t first_n = 0;   // the window's first command
  std::uint64_t commands = 0;  // commands in it, refreshes included
  std::int64_t open_ts = kNoTime;
  // rate and PTZ: the commanded direction (+1, -1; 0 a stop) and the raw
  // count; angle: the target in degrees (clamped to the field's range)
  int sign = 0;
  std::int64_t raw = 0;
  double target = 0;
  // As the command says it: angle, the value decoded from the wire (the
  // catalog's scale and sign); rate, the speed in deg/s (its magnitude,
  // under field evidence: the field's unit).
  double wire = 0;
  // Why `target` and `sign` differ from the wire's sign: the field's sign
  // of this command (top::MotionAxis::sign_in) and the model's sign trait
  // (top::sign_trait_factor), each +1 or -1.
  std::int8_t field_sign = 1, trait = 1;
  double from = 0, to = 0;  // the attitude at the window's start and end, deg
  double seconds = 0;       // between those two reports
  bool acked = false;       // the device echoed one of its commands
  // the model's sign trait is unknown (top::sign_trait_factor 0): which way
  // the command should turn the gimbal cannot be told
  bool ambiguous = false;
  // yaw: the turn from `from` to `to` across whole turns (Unwrap), when
  // `whole`; a window that turns past 180 deg measured the short way round
  // reads the other way
  double turned = 0;
  bool whole = false;
  // angle: the command's range keeps the axis off +-180 (Topotek yaw
  // +-150): the gimbal goes from +140 to -140 through 0, never across
  bool linear = false;
  double moved() const noexcept;  // to - from: `turned`, else yaw the short way round
  // target - from (and -target - from, the other convention's), the way the
  // gimbal has to turn: the short way round for yaw, unless `linear`
  double step() const noexcept;
  double mirror_step() const noexcept;
};

// b - a in degrees, the short way round for yaw (axis 0).
double angle_delta(int axis, double a, double b) noexcept;
// "up", "down", "right", "left" for a direction on an axis.
std::string_view direction_word(int axis, int sign) noexcept;
// "+10.0", "-3.5"; a value that rounds to zero is "+0.0"
std::string signed_text(double v);
// The command of a window as it reads on the wire and what it means for
// the attitude: "GAY to -20.0 deg", "GIP +30.0 deg (pitch down positive on
// the wire: a target of -30.0 deg)", "GSP 20 (10.0 deg/s up)".
std::string command_text(const Judged& j);

}  // namespace topdump::diag
