// tracking-refused: the device answers tracking with a state that refuses
// it (top::refuses_tracking: Topotek TRC state 4, this lens does not
// track). State 3, temporarily lost, is no refusal.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class TrackingWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::tracking_refused};
  void reply(top::Dialect d, std::string_view ident, std::string_view data, std::uint64_t n,
             std::int64_t ts, int dir) noexcept {
    if (top::refuses_tracking(d, ident, data)) c_.add(n, ts, ident, dir);
  }
  std::optional<Found> verdict() const;

 private:
  Case c_;
};

}  // namespace topdump::diag
