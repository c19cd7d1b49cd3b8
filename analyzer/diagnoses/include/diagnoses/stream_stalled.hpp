// stream-stalled: a push stream stops for more than 3 periods (stream_gap,
// and more than kMinStallUs) and resumes.
// The period is the one asked for or, when the stream runs slower than
// asked (stream-rate's case) or no rate was asked, the stream's own typical
// interval, so that one cause gives one item: a steady 10 Hz stream asked
// for at 50 Hz is off its rate, never stalled.
#pragma once

#include <algorithm>
#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

// A push stream's interval is a gap when it is longer than kGapPeriods of
// the stream's periods: the one rule of stream-stalled (StallWatch, which
// chooses the period) and of the gaps the report lists per stream.
inline constexpr int kGapPeriods = 3;
constexpr bool stream_gap(double interval_us, double period_us) noexcept {
  return interval_us > kGapPeriods * period_us;
}

class StallWatch {
 public:
  // A push of the stream, frame n at ts; asked_hz 0 when no rate was asked.
  // Inline: the session calls it for every push.
  void push(std::uint64_t n, std::int64_t ts, double asked_hz) noexcept;
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::stream_stalled};
  // The diagnosis for the stream `ident`, pushed in direction `dir`, when
  // it stalled.
  std::optional<Found> verdict(std::string_view ident, int dir) const;
  std::uint64_t first_push() const noexcept { return first_n_; }
  // The time the stream spent stalled, microseconds (the stream's rate
  // without it is what stream-rate judges when it stalled: one cause, one
  // item).
  std::int64_t stalled_us() const noexcept { return stalled_us_; }

 private:
  // A stop longer than kGapPeriods periods (the period the push judged by).
  void stalled(std::uint64_t n, std::int64_t ts, double period) noexcept;
  // a shorter stop is the link's bunching (top::stream_stall_min_ms)
  static constexpr std::int64_t kMinStallUs = top::stream_stall_min_ms * 1000;
  std::int64_t last_ = kNoTime;
  double typical_us_ = 0;  // running mean of the intervals that were no stall
  std::uint32_t intervals_ = 0;
  std::uint64_t first_n_ = 0;
  // One frame per stall: the last push before it, at its time; the case
  // ends (last_ts) when the last stall resumed.
  Case stalls_;
  std::uint64_t last_n_ = 0, resumed_n_ = 0;  // the last push; the first stall's resuming push
  std::int64_t longest_us_ = 0, longest_at_ = kNoTime, stalled_us_ = 0;
  double period_us_ = 0;                // the period the longest stall was judged by
  double asked_hz_ = 0, asked_us_ = 0;  // the rate last asked, and its period
};

inline void StallWatch::push(std::uint64_t n, std::int64_t ts, double asked_hz) noexcept {
  if (first_n_ == 0) first_n_ = n;
  if (ts == kNoTime) return;
  if (last_ == kNoTime || ts < last_) {
    last_ = ts;
    last_n_ = n;
    return;
  }
  const auto dt = static_cast<double>(ts - last_);
  // Judged once the stream has shown its pace (four intervals).
  if (asked_hz != asked_hz_) {  // the period, worked out when the rate asked changes
    asked_hz_ = asked_hz;
    asked_us_ = asked_hz > 0 ? 1e6 / asked_hz : 0;
  }
  const double period = std::max(asked_us_, typical_us_);
  if (intervals_ >= 4 && period > 0 && stream_gap(dt, period)) {
    // a bunch of the link is neither a stall nor the stream's pace
    if (dt > static_cast<double>(kMinStallUs)) stalled(n, ts, period);
  } else if (intervals_ < 16) {
    // a running mean over the first 16 intervals, then a slow follower
    // (a weight of 1/16, without a division per push)
    ++intervals_;
    typical_us_ += (dt - typical_us_) / intervals_;
  } else {
    typical_us_ += (dt - typical_us_) * (1.0 / 16);
  }
  last_ = ts;
  last_n_ = n;
}

}  // namespace topdump::diag
