// Which liveness probe a run (and a fuzz session) uses: the matrix's own
// `probe` when it names one, else the catalog's probes for the model
// (top/probe.hpp) tried in order until one is answered. A device that
// answers another probe, or only sends other frames, is reachable: "probe
// unanswered: IDENT" names what it left unanswered, apart from an
// unreachable target that sent nothing at all.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "conf/matrix.hpp"
#include "conf/probe.hpp"

namespace topconf {

// The probes to try for `m` with the client address `client`, in order.
std::vector<Probe> probes_for(const Matrix& m, char client);

struct ProbeChoice {
  std::optional<Probe> probe;           // the first one answered
  std::vector<std::string> unanswered;  // the identifiers tried before it, unanswered
  bool heard = false;                   // some frame came back (the device is reachable)
  // "probe unanswered: VER" ("VER, GIA" for several); empty when none was.
  std::string note() const;
};

// Tries each of `probes` up to `tries` times with `once` (one send and
// wait) until one is answered.
ProbeChoice choose_probe(const std::vector<Probe>& probes, int tries,
                         const std::function<ProbeHeard(const Probe&)>& once);

}  // namespace topconf
