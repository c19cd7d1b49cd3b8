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
  std::snprintf(b, sizeof b, "%+.1f", v);
  return b;
}

}  // namespace topdump::diag
