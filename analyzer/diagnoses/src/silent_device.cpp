#include "diagnoses/silent_device.hpp"

#include <cstdio>

#include "top/text.hpp"

namespace topdump::diag {

void SilentStretch::add(std::uint64_t n, std::int64_t ts, std::string_view ident, int dir,
                        bool timed_out) {
  if (c_.frames == 0) idents_.clear();
  c_.add(n, ts, ident, dir);
  timed_out_ |= timed_out;
  last_n_ = n;
  const std::string id = top::escape(ident);
  if (idents_.find(id) == std::string::npos && idents_.size() < 64)
    idents_ += (idents_.empty() ? "" : ", ") + id;
}

std::string SilentStretch::figure() const {
  char span[32];
  std::snprintf(span, sizeof span, "%.3f", static_cast<double>(c_.last_ts - c_.first_ts) / 1e6);
  return "the device was silent: " + std::to_string(c_.frames) + " requests (" + idents_ +
         ") from frame " + std::to_string(c_.first_frame) + " to frame " + std::to_string(last_n_) +
         " over " + span + " s got no response";
}

std::optional<Found> SilentStretch::verdict() const {
  if (c_.frames < 2 || !timed_out_) return std::nullopt;
  return Found{top::Diagnosis::silent_device, c_, -1, figure()};
}

}  // namespace topdump::diag
