#include "top/probe.hpp"

#include "top/device.hpp"

namespace top {

namespace {

struct ProbeRow {
  Dialect dialect;
  std::string_view ident;
  char control;
  std::string_view data;
  std::string_view evidence;
};

// In the order to try them: a read that is answered by a reply of its own
// first (a hung device may still stream), then the attitude stream's switch,
// whose answer is a push. docs/sources/ardupilot.md sections 3, 4 and 8 give what
// ArduPilot's simulators answer.
constexpr ProbeRow kProbes[] = {
    {Dialect::skydroid, "AWB", 'r', "00",
     "SkyDroid 4.5.1: every model has the white-balance read (topsim answers it)"},
    {Dialect::skydroid, "VER", 'r', "00",
     "SkyDroid 4.11; ArduPilot's AP_Mount_SkyDroid reads it until answered and its "
     "SIM_SkyDroid answers any VER (#TPUD6rVERV1.0.038; docs/sources/ardupilot.md sections 2.2, "
     "4)"},
    {Dialect::skydroid, "GAA", 'w', "01",
     "SkyDroid 3.3.2.1: GAA 01 asks GAC at 1 Hz; ArduPilot's driver sends #TPUG2wGAA323A once "
     "a second and SIM_SkyDroid answers any GAA with a GAC at once (docs/sources/ardupilot.md "
     "sections 2.2, 4)"},
    {Dialect::topotek, "VER", 'r', "00",
     "Topotek 4.5.1: the serial number read (topsim answers it)"},
    {Dialect::topotek, "GIA", 'w', "01",
     "Topotek 4.3.6 (GIA 01 pushes GIC) and the field (GIA frames): ArduPilot's "
     "AP_Mount_Topotek sends #TPUG2wGIA013E once a second, SIM_Topotek answers any GIA with "
     "a GIA frame at once, a real Topotek camera answers the GIC query with GIA (PixEagle "
     "session 20260917T044930Z-queries; docs/sources/ardupilot.md sections 1.2, 3, 8.1)"},
};

}  // namespace

bool LivenessProbe::switches_push(Dialect d, std::string_view id) const noexcept {
  if (control != 'w') return false;
  for (const StreamSpec& s : streams())
    if (s.dialect == d && s.request == ident && s.push == id && s.sender == Sender::device)
      return true;
  return false;
}

std::vector<LivenessProbe> liveness_probes(Model model) {
  std::vector<LivenessProbe> v;
  const Dialect d = dialect_of(model);
  if (model == Model::unknown) return v;
  for (const ProbeRow& p : kProbes) {
    const CommandSpec* c = p.dialect == d ? find_command(d, p.ident) : nullptr;
    if (!c || !c->supports(model) || !c->has_control(p.control)) continue;
    std::string_view answer = p.ident;
    if (p.control == 'w')
      if (const StreamSpec* s = stream_enabled_by(d, p.ident, Profile::field)) answer = s->push;
    v.push_back({p.ident, c->address, p.control, p.data, answer, p.evidence});
  }
  return v;
}

}  // namespace top
