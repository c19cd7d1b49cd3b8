// The liveness probe, shared by topconf run (before and between cases) and
// topconf fuzz (after each case): a frame the device must answer.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "conf/link.hpp"
#include "top/probe.hpp"

namespace topconf {

struct Probe {
  std::string bytes;  // the frame sent
  std::string ident;  // what an answer carries
  char control = 0;   // and with this control (0: any)
  // A probe of the catalog (top/probe.hpp) is also answered by the frames
  // it names, such as the push of the stream it switches on (GAA: GAC).
  std::optional<top::LivenessProbe> liveness;
  top::Dialect dialect = top::Dialect::unknown;
  // A probe that switches a stream on (GIA 01, GAA 01) switches it off
  // again with these bytes once answered (the same write with 00), so its
  // pushes do not run into the cases (a real SIP's GIA push is the very
  // frame that answers a GIC query); empty for any other probe.
  std::string off;
  // From a frame's bytes: its identifier, and its control when `match_control`.
  static Probe of(std::string bytes, bool match_control);
  // Whether the device frame `f` answers the probe (an ERE does: the device
  // is alive).
  bool answered_by(const top::Frame& f) const;
};

// What came back to one probe.
enum class ProbeHeard {
  answer,  // a frame that answers it
  other,   // frames, none of them an answer (the device is reachable)
  nothing  // no frame at all
};

// Sends `p` once over `link` and waits up to `timeout_us` for its answer:
// a frame of its identifier (and control) or one the catalog's probe names,
// even damaged, or the error reply. Another frame, a push too, is no answer
// (a hung device may still stream) but shows the device is reachable.
// Once answered, a stream switch's `off` is sent and its echo awaited
// (within the same timeout), so no push of the probe's stream follows.
ProbeHeard probe_once(FrameLink& link, const Probe& p, std::uint64_t timeout_us);

}  // namespace topconf
