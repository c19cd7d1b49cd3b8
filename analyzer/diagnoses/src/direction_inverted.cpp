#include "diagnoses/direction_inverted.hpp"

#include <cmath>

namespace topdump::diag {

void DirectionWatch::window(const Judged& j) {
  const double moved = j.moved();
  if (j.ambiguous || std::fabs(moved) < kMinMoved) return;
  int want = j.sign;  // rates and PTZ: the commanded direction
  if (j.spec->kind == top::MotionKind::angle) {
    const double step = j.step();
    if (std::fabs(step) < kMinStep) return;
    // The other convention's target is -target: when it lies on the same
    // side of the start (a return to 0, a target nearer 0 than the start),
    // both conventions move the gimbal the same way and the window tells
    // neither from the other. Counted as right, such windows outvoted the
    // ones that showed the inversion.
    const double mirror = j.mirror_step();
    if (std::fabs(mirror) >= kMinStep && (mirror > 0) == (step > 0)) return;
    want = step > 0 ? 1 : -1;
  }
  if (want == 0) return;
  const auto kind = static_cast<std::size_t>(j.spec->kind);  // angle 0, rate 1, PTZ 2
  Slot& s = slots_[static_cast<std::size_t>(j.axis) * 3 + kind];
  if ((moved > 0) == (want > 0)) {
    ++s.right;
    return;
  }
  if (s.inverted++ == 0) s.first = j;
  s.c.add(j.first_n, j.open_ts, j.spec->ident, j.dir);
}

std::optional<Found> DirectionWatch::verdict(std::size_t i) const {
  const Slot& s = slots_[i];
  if (s.inverted == 0 || s.inverted <= 2 * s.right) return std::nullopt;
  const Judged& j = s.first;
  const std::string axis(top::to_string(static_cast<top::Axis>(j.axis)));
  Found f{top::Diagnosis::direction_inverted, s.c, j.axis, {}};
  std::string& t = f.figure;
  const double moved = j.moved();
  t = command_text(j) + ": " + axis;
  if (j.spec->kind == top::MotionKind::angle)
    t += " went from " + signed_text(j.from) + " to " + signed_text(j.to) + " deg (" +
         std::string(direction_word(j.axis, moved > 0 ? 1 : -1)) + "), away from it";
  else
    t += " moved " + signed_text(moved / j.seconds) + " deg/s (" +
         std::string(direction_word(j.axis, moved > 0 ? 1 : -1)) + ")";
  t += " in " + seconds_text(static_cast<std::int64_t>(j.seconds * 1e6)) + " s by " +
       std::string(j.attitude) + "; " + std::to_string(s.inverted) + " of " +
       std::to_string(s.inverted + s.right) + " " + axis + " " +
       std::string(top::to_string(j.spec->kind)) + " window" +
       (s.inverted + s.right == 1 ? "" : "s") + " moved the other way";
  return f;
}

}  // namespace topdump::diag
