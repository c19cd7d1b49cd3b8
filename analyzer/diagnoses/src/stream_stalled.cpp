#include "diagnoses/stream_stalled.hpp"

#include <algorithm>

namespace topdump::diag {

void StallWatch::stalled(std::uint64_t n, std::int64_t ts, double period) noexcept {
  if (!stalls_.any()) resumed_n_ = n;
  stalls_.add(last_n_, last_, {}, 0);
  stalls_.last_ts = ts;
  stalled_us_ += ts - last_;
  if (ts - last_ > longest_us_) {
    longest_us_ = ts - last_;
    longest_at_ = last_;
    period_us_ = period;
  }
}

std::optional<Found> StallWatch::verdict(std::string_view ident, int dir) const {
  if (!stalls_.any()) return std::nullopt;
  Found f{top::Diagnosis::stream_stalled, stalls_, -1, {}};
  f.c.dir = dir;
  for (std::size_t i = 0; i < 3; ++i) f.c.ident[i] = i < ident.size() ? ident[i] : '\0';
  f.figure = std::string(ident) + " push stopped " + std::to_string(stalls_.frames) +
             (stalls_.frames == 1 ? " time" : " times") + " for more than " +
             std::to_string(kGapPeriods) + " periods (period " +
             seconds_text(static_cast<std::int64_t>(period_us_)) + " s) and resumed; longest " +
             seconds_text(longest_us_) + " s from " + time_text(longest_at_) +
             "; the first stopped after frame " + std::to_string(stalls_.first_frame) +
             " and resumed at frame " + std::to_string(resumed_n_);
  return f;
}

}  // namespace topdump::diag
