#include "diagnoses/judged.hpp"

#include <cmath>
#include <cstdio>

namespace topdump::diag {

double angle_delta(int axis, double a, double b) noexcept {
  double d = b - a;
  if (axis == static_cast<int>(top::Axis::yaw)) d = top::short_way(d);
  return d;
}

double Judged::moved() const noexcept {
  if (whole) return turned;
  return linear ? to - from : angle_delta(axis, from, to);
}

double Judged::step() const noexcept {
  return linear ? target - from : angle_delta(axis, from, target);
}

double Judged::mirror_step() const noexcept {
  return linear ? -target - from : angle_delta(axis, from, -target);
}

std::string_view direction_word(int axis, int sign) noexcept {
  if (axis == static_cast<int>(top::Axis::pitch)) return sign > 0 ? "up" : "down";
  return sign > 0 ? "right" : "left";
}

std::string signed_text(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%+.1f", std::fabs(v) < 0.05 ? 0.0 : v);
  return b;
}

std::string command_text(const Judged& j) {
  const std::string ident(j.spec->ident);
  char b[48];
  switch (j.spec->kind) {
    case top::MotionKind::angle: {
      if (j.field_sign * j.trait > 0) return ident + " to " + signed_text(j.target) + " deg";
      const auto axis = static_cast<top::Axis>(j.axis);
      const std::string why =
          j.field_sign < 0 ? std::string(top::to_string(axis)) + " " +
                                 std::string(direction_word(j.axis, -1)) + " positive on the wire"
                           : "the model's inverted " + std::string(top::to_string(axis));
      return ident + " " + signed_text(j.wire) + " deg (" + why + ": a target of " +
             signed_text(j.target) + " deg)";
    }
    case top::MotionKind::rate:
      std::snprintf(b, sizeof b, " %lld (%.1f deg/s ", static_cast<long long>(j.raw), j.wire);
      return ident + b + std::string(direction_word(j.axis, j.sign)) + ")";
    default:
      return ident + " (" + std::string(direction_word(j.axis, j.sign)) + ")";
  }
}

}  // namespace topdump::diag
