// Requests that carry a cause for the device to drop them, one case per
// cause: reply-interface (a network client that names itself U, the UART,
// in Topotek requests: the client's deviation, reported whether or not the
// device answered, with how many went unanswered), dropped-bad-checksum and
// dropped-checksum-case (the device drops a frame it cannot trust, or
// whose checksum digits are lowercase: each unanswered request). The
// session decides the cause once (Cause, session/requests.cpp).
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class DroppedWatch {
 public:
  // A request unanswered for the cause diagnosed as `d` (one of the three).
  void add(top::Diagnosis d, std::uint64_t n, std::int64_t ts, std::string_view ident,
           int dir) noexcept {
    if (const int i = slot(d); i >= 0) cases_[static_cast<std::size_t>(i)].add(n, ts, ident, dir);
  }
  // A request of case `d` went unanswered (reply-interface: its case
  // holds every such request, answered or not).
  void unanswered(top::Diagnosis d) noexcept {
    if (const int i = slot(d); i >= 0) ++unanswered_[static_cast<std::size_t>(i)];
  }
  // The diagnoses found, in the table's order.
  template <class Out>
  void verdicts(Out&& out) const {
    for (top::Diagnosis d : kCodes)
      if (std::optional<Found> f = verdict(d)) out(std::move(*f));
  }
  std::optional<Found> verdict(top::Diagnosis d) const;

 private:
  static constexpr std::array<top::Diagnosis, 3> kCodes = {top::Diagnosis::reply_interface,
                                                           top::Diagnosis::dropped_bad_checksum,
                                                           top::Diagnosis::dropped_checksum_case};
  static int slot(top::Diagnosis d) noexcept {
    for (std::size_t i = 0; i < kCodes.size(); ++i)
      if (kCodes[i] == d) return static_cast<int>(i);
    return -1;
  }
  std::array<Case, 3> cases_{};
  std::array<std::uint64_t, 3> unanswered_{};
};

}  // namespace topdump::diag
