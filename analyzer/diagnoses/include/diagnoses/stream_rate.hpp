// stream-rate: a periodic push stream that a switch asked to push at a
// rate runs more than top::stream_rate_tolerance off it, measured from its
// first push to its last. A stream that stalled (stream-stalled) is judged
// without its stalls: at the rate asked, the stall is the cause (one cause,
// one item). The rate rule exists here only; the statistics and the report
// read it (StreamStat::off_rate, session/stats.hpp).
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

// Pushes per second from the first push to the last; 0 for fewer than two
// pushes or no time between them.
double measured_hz(std::uint64_t frames, std::int64_t first, std::int64_t last) noexcept;
// Whether a measured rate is within the tolerance of the rate asked.
bool rate_within(double hz, double asked_hz) noexcept;
// Asked a rate, measured one, and more than the tolerance off it.
inline bool off_rate(double hz, double asked_hz) noexcept {
  return asked_hz > 0 && hz > 0 && !rate_within(hz, asked_hz);
}

// A periodic stream's figures at its end.
struct StreamRun {
  std::string_view ident;     // the push (GAC, GIC)
  std::string_view asked_by;  // its switch (GAA, GIA)
  double asked_hz = 0;
  std::uint64_t frames = 0;
  std::int64_t first = kNoTime, last = kNoTime;
  std::uint64_t first_push = 0;  // its first frame
  int dir = 0;                   // the direction the device pushes in
  bool stalled = false;          // stream-stalled found it stalled...
  std::int64_t stalled_us = 0;   // ...this long in all
};

struct StreamRate {
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::stream_rate};
  static std::optional<Found> verdict(const StreamRun& s);
};

}  // namespace topdump::diag
