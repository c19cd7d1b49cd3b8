// stream-never-started: a switch asked for a push stream, the device
// answered the switch, and no push came in the time the stream should have
// shown itself (three periods, at least a second) before the conversation
// ended. The field note: a camera pushes only once it outputs video.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class NeverStartedWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::stream_never_started};
  // The switch (frame n at ts) was sent; again while the stream waits
  // counts toward the same case.
  void asked(std::uint64_t n, std::int64_t ts, std::string_view switch_ident) noexcept {
    switches_.add(n, ts, switch_ident, 0);
  }
  // The device answered the switch.
  void answered() noexcept { answered_ = true; }
  // The diagnosis when no push came by `end` (the conversation's last
  // frame); asked_hz 0 when the switch gives no rate.
  std::optional<Found> verdict(std::string_view push_ident, std::uint64_t pushes, double asked_hz,
                               std::int64_t end) const;

 private:
  Case switches_;
  bool answered_ = false;
};

}  // namespace topdump::diag
