#include "diagnoses/stream_stalled.hpp"

#include <algorithm>

namespace topdump::diag {

void StallWatch::push(std::uint64_t n, std::int64_t ts, double asked_hz) noexcept {
  if (first_n_ == 0) first_n_ = n;
  if (ts == kNoTime) return;
  if (last_ == kNoTime || ts < last_) {
    last_ = ts;
    return;
  }
  const auto dt = static_cast<double>(ts - last_);
  // Judged once the stream has shown its pace (four intervals).
  const double asked_us = asked_hz > 0 ? 1e6 / asked_hz : 0;
  const double period = std::max(asked_us, typical_us_);
  const bool judged = intervals_ >= 4 && period > 0 && dt > kPeriods * period;
  if (judged && dt <= static_cast<double>(kMinStallUs)) {
    last_ = ts;  // a bunch of the link: neither a stall nor the stream's pace
    return;
  }
  if (judged) {
    stalls_.add(n, last_, {}, 0);
    stalled_us_ += ts - last_;
    if (ts - last_ > longest_us_) {
      longest_us_ = ts - last_;
      longest_at_ = last_;
      period_us_ = period;
    }
  } else {
    // a running mean over the first 16 intervals, then a slow follower
    // (a weight of 1/16, without a division per push)
    if (intervals_ < 16) {
      ++intervals_;
      typical_us_ += (dt - typical_us_) / intervals_;
    } else {
      typical_us_ += (dt - typical_us_) * (1.0 / 16);
    }
  }
  last_ = ts;
}

std::optional<Found> StallWatch::verdict(std::string_view ident) const {
  if (!stalls_.any()) return std::nullopt;
  Found f{top::Diagnosis::stream_stalled, stalls_, -1, {}};
  for (std::size_t i = 0; i < 3; ++i) f.c.ident[i] = i < ident.size() ? ident[i] : '\0';
  f.figure = std::string(ident) + " push stopped " + std::to_string(stalls_.frames) +
             (stalls_.frames == 1 ? " time" : " times") + " for more than 3 periods (period " +
             seconds_text(static_cast<std::int64_t>(period_us_)) + " s) and resumed; longest " +
             seconds_text(longest_us_) + " s from " + time_text(longest_at_) +
             "; the first resumed at frame " + std::to_string(stalls_.first_frame);
  return f;
}

}  // namespace topdump::diag
