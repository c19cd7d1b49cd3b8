#include "diagnoses/axis_left_moving.hpp"

#include <cmath>
#include <cstdio>

#include "top/diagnoses.hpp"

namespace topdump::diag {

void LeftMovingWatch::at_end(const LeftMoving& m) {
  if (m.sign == 0 || m.end_ts - m.last_ts < top::attitude_stale_ms * 1000 || m.mark_ts == kNoTime ||
      m.mark_ts <= m.last_ts)
    return;
  const double after = m.whole ? m.after : angle_delta(m.axis, m.at_last, m.at_end);
  const double tail = angle_delta(m.axis, m.at_mark, m.at_end);
  // moved since the last command, and still moving the same way at the end
  // (which way is not judged: a model's sign trait may turn it)
  if (std::fabs(after) < kMinMoved || tail * (after > 0 ? 1 : -1) < kStillMoving) return;
  const std::string axis(top::to_string(static_cast<top::Axis>(m.axis)));
  Case c;
  c.add(m.last_n, m.last_ts, m.spec->ident, m.dir);
  Found f{top::Diagnosis::axis_left_moving, c, m.axis, {}};
  const double tail_s = static_cast<double>(m.end_ts - m.mark_ts) / 1e6;
  char rate[48] = "";
  if (m.spec->kind != top::MotionKind::ptz)
    std::snprintf(rate, sizeof rate, " %lld (%.1f deg/s)", static_cast<long long>(m.raw), m.speed);
  f.figure = std::string(m.spec->ident) + rate + " at " + time_text(m.last_ts) + " was the last " +
             axis + " command and no stop followed: " + axis + " moved " + signed_text(after) +
             " deg in the " + seconds_text(m.end_ts - m.last_ts) + " s to the end by " +
             std::string(m.attitude) + ", still " + signed_text(tail / tail_s) +
             " deg/s at the end";
  found_[static_cast<std::size_t>(m.axis)] = std::move(f);
}

}  // namespace topdump::diag
