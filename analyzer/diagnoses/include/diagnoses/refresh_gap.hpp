// refresh-gap: a rate command not refreshed within the speed-refresh limit
// (top::speed_refresh_trait): the firmware stops the motors. A gap is a
// non-zero rate on an axis whose next command there (a rate, a PTZ stop),
// or the conversation's end, came later than the limit.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

// A rate command held `held_us` without a refresh stopped the motors when
// that is longer than the speed-refresh limit `limit_us` (0: none applies):
// the one rule of refresh-gap (MotionTrack, which chooses the model and
// the end of the wait) and of the gaps the report lists per rate command.
constexpr bool refresh_missed(std::int64_t held_us, std::int64_t limit_us) noexcept {
  return limit_us > 0 && held_us > limit_us;
}

class RefreshWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::refresh_gap};
  // The rate command frame n at ts on `axis` went `gap_us` without a refresh.
  void gap(std::uint64_t n, std::int64_t ts, std::string_view ident, int axis, int dir,
           std::int64_t gap_us, std::uint32_t limit_ms) noexcept;
  std::optional<Found> verdict() const;

 private:
  Case c_;
  int axis_ = -1;
  std::uint32_t limit_ms_ = 0;
  std::int64_t longest_us_ = 0, longest_at_ = kNoTime;
  char longest_ident_[3] = {};
};

}  // namespace topdump::diag
