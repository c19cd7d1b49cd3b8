// Requests that carry a cause for the device to drop them, one case per
// cause that is a diagnosis (diagnosis_of, diagnoses/cause.hpp):
// reply-interface (a network client that names itself U, the UART, in
// Topotek requests: the client's deviation, reported whether or not the
// device answered, with how many went unanswered), dropped-bad-checksum and
// dropped-checksum-case (the device drops a frame it cannot trust, or whose
// checksum digits are lowercase: each unanswered request). The session
// decides each request's cause once (session/requests.cpp, cause_of) and
// tells this detector of every request and every unanswered one.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"
#include "diagnoses/cause.hpp"

namespace topdump::diag {

class DroppedWatch {
 public:
  static constexpr std::array<top::Diagnosis, 3> codes = {top::Diagnosis::reply_interface,
                                                          top::Diagnosis::dropped_bad_checksum,
                                                          top::Diagnosis::dropped_checksum_case};
  // A request sent with cause `c`: the client's deviation is its case
  // whatever the device does with it (reply-interface).
  void request(Cause c, std::uint64_t n, std::int64_t ts, std::string_view ident,
               int dir) noexcept {
    if (c == Cause::uart_source) at(top::Diagnosis::reply_interface).add(n, ts, ident, dir);
  }
  // A request of cause `c` went unanswered: a dropped frame is the case
  // (dropped-*); reply-interface counts it.
  void unanswered(Cause c, std::uint64_t n, std::int64_t ts, std::string_view ident,
                  int dir) noexcept {
    const std::optional<top::Diagnosis> d = diagnosis_of(c);
    if (d == top::Diagnosis::reply_interface)
      ++unanswered_[slot(*d)];
    else if (d == top::Diagnosis::dropped_bad_checksum ||
             d == top::Diagnosis::dropped_checksum_case)
      at(*d).add(n, ts, ident, dir);
  }
  // The diagnoses found, in the table's order.
  template <class Out>
  void verdicts(Out&& out) const {
    for (top::Diagnosis d : codes)
      if (std::optional<Found> f = verdict(d)) out(std::move(*f));
  }
  std::optional<Found> verdict(top::Diagnosis d) const;

 private:
  static constexpr std::size_t slot(top::Diagnosis d) noexcept {
    std::size_t i = 0;
    while (i + 1 < codes.size() && codes[i] != d) ++i;
    return i;
  }
  Case& at(top::Diagnosis d) noexcept { return cases_[slot(d)]; }
  std::array<Case, 3> cases_{};
  std::array<std::uint64_t, 3> unanswered_{};
};

}  // namespace topdump::diag
