#include "diagnoses/dropped_requests.hpp"

#include <algorithm>

#include "top/text.hpp"

namespace topdump::diag {

std::optional<Found> DroppedWatch::verdict(top::Diagnosis d) const {
  if (std::find(codes.begin(), codes.end(), d) == codes.end()) return std::nullopt;
  const std::size_t i = slot(d);
  const Case& c = cases_[i];
  if (!c.any()) return std::nullopt;
  Found f{d, c, -1, {}};
  const std::string first = " (the first: " + top::escape(std::string_view(c.ident, 3)) +
                            " at frame " + std::to_string(c.first_frame) + ")";
  const std::string n = std::to_string(c.frames) + (c.frames == 1 ? " request" : " requests");
  if (d == top::Diagnosis::reply_interface) {
    const std::uint64_t lost = unanswered_[i];
    f.figure = "the client sent " + n + " with source U (the UART's address) over the network" +
               first + "; a network client is P (Topotek V1.1.3)" +
               (lost == 0 ? std::string(", and none that expects an answer went unanswered")
                          : ": " + std::to_string(lost) + " got no answer");
    return f;
  }
  f.figure = n +
             (d == top::Diagnosis::dropped_bad_checksum ? " with a bad checksum"
                                                        : " with a lowercase checksum") +
             " got no answer" + first;
  return f;
}

}  // namespace topdump::diag
