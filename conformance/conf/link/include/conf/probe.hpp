// The liveness probe, shared by topconf run (before and between cases) and
// topconf fuzz (after each case): a frame the device must answer.
#pragma once

#include <cstdint>
#include <string>

#include "conf/link.hpp"

namespace topconf {

struct Probe {
  std::string bytes;  // the frame sent
  std::string ident;  // what an answer carries
  char control = 0;   // and with this control (0: any)
  // From a frame's bytes: its identifier, and its control when `match_control`.
  static Probe of(std::string bytes, bool match_control);
};

// Sends `p` once over `link` and waits up to `timeout_us` for its answer:
// a frame of its identifier (and control), even damaged, or the error
// reply. Pushes do not count: a hung device may still stream.
bool probe_answered(FrameLink& link, const Probe& p, std::uint64_t timeout_us);

}  // namespace topconf
