#include "conf/probe.hpp"

#include "top/device.hpp"
#include "top/frame.hpp"

namespace topconf {

Probe Probe::of(std::string bytes, bool match_control) {
  Probe p;
  auto pr = top::parse_exact(bytes);
  if (pr.status == top::ParseStatus::frame) {
    p.ident = std::string(pr.frame.ident_view());
    if (match_control) p.control = pr.frame.control;
  } else if (bytes.size() >= top::prefix_size) {
    p.ident = bytes.substr(7, 3);  // the identifier's place in a #TP/#tp frame
  }
  p.bytes = std::move(bytes);
  return p;
}

bool Probe::answered_by(const top::Frame& f) const {
  const std::string_view id = f.ident_view();
  if (top::is_error_reply(id)) return true;
  if (liveness && liveness->switches_push(dialect, id)) return true;
  return id == ident && (!control || f.control == control);
}

ProbeHeard probe_once(FrameLink& link, const Probe& p, std::uint64_t timeout_us) {
  link.send(p.bytes);
  const std::uint64_t deadline = link.now() + timeout_us;
  Received r;
  ProbeHeard heard = ProbeHeard::nothing;
  while (link.next(deadline, r)) {
    if (p.answered_by(r.frame)) return ProbeHeard::answer;
    heard = ProbeHeard::other;
  }
  return heard;
}

}  // namespace topconf
