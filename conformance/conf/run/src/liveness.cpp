#include "conf/liveness.hpp"

#include "top/device.hpp"

namespace topconf {

std::vector<Probe> probes_for(const Matrix& m, char client) {
  std::vector<Probe> v;
  std::string bytes, err;
  if (m.probe) {
    if (resolve_send(*m.probe, m.dialect, client, bytes, err))
      v.push_back(Probe::of(std::move(bytes), true));
    return v;
  }
  for (const top::LivenessProbe& lp : top::liveness_probes(m.model)) {
    SendSpec s;
    s.command = std::string(lp.ident);
    s.control = lp.control;
    s.data = std::string(lp.data);
    if (!resolve_send(s, m.dialect, client, bytes, err)) continue;
    Probe p = Probe::of(std::move(bytes), true);
    p.liveness = lp;
    p.dialect = m.dialect;
    // A stream switch's probe turns the stream off again (00: off, or a rate
    // of 0 Hz; top/device.hpp StreamSpec).
    if (lp.control == 'w' && top::stream_enabled_by(m.dialect, lp.ident)) {
      s.data = "00";
      if (!resolve_send(s, m.dialect, client, p.off, err)) p.off.clear();
    }
    v.push_back(std::move(p));
  }
  return v;
}

std::string ProbeChoice::note() const {
  if (unanswered.empty()) return {};
  std::string s = "probe unanswered: ";
  for (std::size_t i = 0; i < unanswered.size(); ++i) s += (i ? ", " : "") + unanswered[i];
  return s;
}

ProbeChoice choose_probe(const std::vector<Probe>& probes, int tries,
                         const std::function<ProbeHeard(const Probe&)>& once) {
  ProbeChoice c;
  for (const Probe& p : probes) {
    for (int i = 0; i < tries; ++i) {
      const ProbeHeard h = once(p);
      c.heard = c.heard || h != ProbeHeard::nothing;
      if (h == ProbeHeard::answer) {
        c.probe = p;
        return c;
      }
    }
    c.unanswered.push_back(p.ident);
  }
  return c;
}

}  // namespace topconf
