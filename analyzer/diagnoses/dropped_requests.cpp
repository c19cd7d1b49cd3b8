#include "diagnoses/dropped_requests.hpp"

#include "top/text.hpp"

namespace topdump::diag {

std::optional<Found> DroppedWatch::verdict(top::Diagnosis d) const {
  const int i = slot(d);
  if (i < 0) return std::nullopt;
  const Case& c = cases_[static_cast<std::size_t>(i)];
  if (!c.any()) return std::nullopt;
  Found f{d, c, -1, {}};
  const std::string what = d == top::Diagnosis::reply_interface ? " with source U over the network"
                           : d == top::Diagnosis::dropped_bad_checksum
                               ? " with a bad checksum"
                               : " with a lowercase checksum";
  f.figure = std::to_string(c.frames) + (c.frames == 1 ? " request" : " requests") + what +
             " got no answer (the first: " + top::escape(std::string_view(c.ident, 3)) +
             " at frame " + std::to_string(c.first_frame) + ")";
  return f;
}

}  // namespace topdump::diag
