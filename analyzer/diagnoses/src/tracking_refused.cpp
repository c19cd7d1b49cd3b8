#include "diagnoses/tracking_refused.hpp"

namespace topdump::diag {

std::optional<Found> TrackingWatch::verdict() const {
  if (!c_.any()) return std::nullopt;
  Found f{top::Diagnosis::tracking_refused, c_, -1, {}};
  f.figure = "TRC answered state 4 (this lens does not track) " + std::to_string(c_.frames) +
             (c_.frames == 1 ? " time" : " times") + ", first at frame " +
             std::to_string(c_.first_frame);
  return f;
}

}  // namespace topdump::diag
