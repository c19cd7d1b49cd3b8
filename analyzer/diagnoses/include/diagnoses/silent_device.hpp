// silent-device: requests that went unanswered while the device sent
// nothing since each was sent, one stretch at a time; the device was
// silent when the stretch holds several requests and one of them waited
// the whole timeout inside the capture (not just cut off by its end).
// The session tells it each such request (session/requests.cpp) and closes
// the stretch when the device speaks, the direction changes or the
// conversation ends.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class SilentStretch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::silent_device};
  // Request n (ident, sent at ts in direction dir) went unanswered;
  // `timed_out`: it waited the whole timeout inside the capture.
  void add(std::uint64_t n, std::int64_t ts, std::string_view ident, int dir, bool timed_out);
  // The requests so far, their first and last.
  const Case& requests() const noexcept { return c_; }
  std::uint64_t count() const noexcept { return c_.frames; }
  std::uint64_t last_n() const noexcept { return last_n_; }
  int dir() const noexcept { return c_.dir; }
  // "GAY, VER, PTZ": the identifiers, escaped, each once (up to 64 chars).
  const std::string& idents() const noexcept { return idents_; }
  // "the device was silent: 3 requests (...) from frame 1 to frame 9 over
  // 4.000 s got no response"
  std::string figure() const;
  // silent-device, when the stretch shows it.
  std::optional<Found> verdict() const;

 private:
  Case c_;
  std::uint64_t last_n_ = 0;
  std::string idents_;
  bool timed_out_ = false;
};

}  // namespace topdump::diag
