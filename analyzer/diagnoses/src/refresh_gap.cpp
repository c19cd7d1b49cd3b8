#include "diagnoses/refresh_gap.hpp"

namespace topdump::diag {

void RefreshWatch::gap(std::uint64_t n, std::int64_t ts, std::string_view ident, int axis, int dir,
                       std::int64_t gap_us, std::uint32_t limit_ms) noexcept {
  if (!c_.any()) axis_ = axis;
  c_.add(n, ts, ident, dir);
  limit_ms_ = limit_ms;
  if (gap_us > longest_us_) {
    longest_us_ = gap_us;
    longest_at_ = ts;
    for (std::size_t i = 0; i < 3; ++i) longest_ident_[i] = i < ident.size() ? ident[i] : '\0';
  }
}

std::optional<Found> RefreshWatch::verdict() const {
  if (!c_.any()) return std::nullopt;
  Found f{top::Diagnosis::refresh_gap, c_, axis_, {}};
  f.figure = std::to_string(c_.frames) + " rate command" + (c_.frames == 1 ? "" : "s") +
             " not refreshed within " + std::to_string(limit_ms_) + " ms (longest " +
             seconds_text(longest_us_) + " s after the " + std::string(longest_ident_, 3) + " at " +
             time_text(longest_at_) + "): the motors stop";
  return f;
}

}  // namespace topdump::diag
