#include "diagnoses/command_ignored.hpp"

#include <algorithm>
#include <cmath>

namespace topdump::diag {

void IgnoredWatch::window(const Judged& j) {
  const double moved = std::fabs(j.moved());
  if (moved >= kMoving) {
    for (auto& m : movers_)
      if (!m || m == j.spec) {
        m = j.spec;
        break;
      }
    return;
  }
  // the target's distance; either sign's when the model's sign is unknown
  double step = std::fabs(j.step());
  if (j.ambiguous) step = std::min(step, std::fabs(j.mirror_step()));
  if (j.spec->kind != top::MotionKind::angle || !j.acked || moved >= kStill ||
      j.seconds < kMinSeconds || step < kMinStep)
    return;
  for (Entry& e : ignored_)
    if (!e.spec || e.spec == j.spec) {
      if (!e.spec) e.spec = j.spec, e.first = j;
      e.c.add(j.first_n, j.open_ts, j.spec->ident, j.dir);
      return;
    }
}

std::optional<Found> IgnoredWatch::verdict(const Entry& e) const {
  // other commands moved the gimbal: the device moves, this command does not
  const auto other = std::find_if(movers_.begin(), movers_.end(),
                                  [&](const top::MotionSpec* m) { return m && m != e.spec; });
  if (other == movers_.end()) return std::nullopt;
  const Judged& j = e.first;
  const std::string axis(top::to_string(static_cast<top::Axis>(j.axis)));
  Found f{top::Diagnosis::command_ignored, e.c, j.axis, {}};
  f.figure = command_text(j) + " was acknowledged; " + axis + " stayed at " + signed_text(j.to) +
             " deg for " + seconds_text(static_cast<std::int64_t>(j.seconds * 1e6)) + " s by " +
             std::string(j.attitude) + " (" + std::to_string(e.c.frames) + " window" +
             (e.c.frames == 1 ? "" : "s") + "), while " + std::string((*other)->ident) +
             " moved the gimbal";
  return f;
}

}  // namespace topdump::diag
