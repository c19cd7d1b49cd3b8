// axis-left-moving: the last rate command on an axis was non-zero, no stop
// followed, and the gimbal kept moving to the end of the conversation: it
// moved kMinMoved deg or more in the commanded direction after that last
// command, at least top::attitude_stale_ms later, and was still moving in
// the last half second or more of reports.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"
#include "diagnoses/judged.hpp"

namespace topdump::diag {

struct LeftMoving : WindowOf {
  int sign = 0;
  std::int64_t raw = 0;
  double speed = 0;          // rates: the commanded speed, deg/s (magnitude)
  std::uint64_t last_n = 0;  // the last command
  std::int64_t last_ts = kNoTime;
  double at_last = 0, at_mark = 0,
         at_end = 0;  // the attitude then, a little before the end, at the end
  std::int64_t mark_ts = kNoTime, end_ts = kNoTime;
  double after = 0;    // yaw: turned from at_last to at_end across whole turns,
  bool whole = false;  // when known (Unwrap)
};

class LeftMovingWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::axis_left_moving};
  static constexpr double kMinMoved = 3.0, kStillMoving = 1.0;
  // The open rate window of an axis at the conversation's end.
  void at_end(const LeftMoving& m);
  // Whether `axis` was found left moving.
  bool found(int axis) const noexcept { return found_[static_cast<std::size_t>(axis)].has_value(); }
  template <class Out>
  void verdicts(Out&& out) const {
    for (const auto& f : found_)
      if (f) out(Found(*f));
  }

 private:
  std::array<std::optional<Found>, top::axis_count> found_{};
};

}  // namespace topdump::diag
