#include "diagnoses/attitude_stale.hpp"

#include <algorithm>

namespace topdump::diag {

void StaleWatch::command(std::uint64_t n, std::int64_t ts, std::string_view ident, int dir,
                         std::int64_t last_report, std::string_view attitude) noexcept {
  if (episode_ != last_report) {
    episode_ = last_report;
    ++episodes_;
  }
  if (!c_.any()) {
    stopped_at_ = last_report;
    for (std::size_t i = 0; i < 3; ++i) attitude_[i] = i < attitude.size() ? attitude[i] : '\0';
  }
  c_.add(n, ts, ident, dir);
  longest_us_ = std::max(longest_us_, ts - last_report);
}

std::optional<Found> StaleWatch::verdict() const {
  if (c_.frames < kMinCommands) return std::nullopt;
  Found f{top::Diagnosis::attitude_stale, c_, -1, {}};
  const std::string att(attitude_, attitude_[2] ? 3 : 0);
  f.figure = std::to_string(c_.frames) + " non-zero motion commands (the first " +
             std::string(c_.ident, 3) + ") came while the " + att + " attitude was more than " +
             std::to_string(top::attitude_stale_ms) + " ms old; it stopped at " +
             time_text(stopped_at_) + ", and the oldest it was at a command was " +
             seconds_text(longest_us_) + " s" +
             (episodes_ > 1 ? " (" + std::to_string(episodes_) + " times it stopped)" : "");
  return f;
}

}  // namespace topdump::diag
