#include "diagnoses/stream_never_started.hpp"

#include <algorithm>

namespace topdump::diag {

std::optional<Found> NeverStartedWatch::verdict(std::string_view push, std::uint64_t pushes,
                                                double asked_hz, std::int64_t end) const {
  if (pushes || !answered_ || !switches_.any() || switches_.first_ts == kNoTime || end == kNoTime)
    return std::nullopt;
  const double wait_us = std::max(1e6, asked_hz > 0 ? 3e6 / asked_hz : 0.0);
  const std::int64_t waited = end - switches_.first_ts;
  if (static_cast<double>(waited) < wait_us) return std::nullopt;
  Found f{top::Diagnosis::stream_never_started, switches_, -1, {}};
  const std::string sw(switches_.ident, 3);
  f.figure = sw + " asked for the " + std::string(push) + " push " +
             std::to_string(switches_.frames) + (switches_.frames == 1 ? " time" : " times") +
             " from frame " + std::to_string(switches_.first_frame) +
             " and the device answered, but no " + std::string(push) + " came in " +
             seconds_text(waited) + " s";
  return f;
}

}  // namespace topdump::diag
