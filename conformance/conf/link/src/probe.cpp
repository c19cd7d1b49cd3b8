#include "conf/probe.hpp"

#include <algorithm>

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

namespace {

// Sends the probe's `off` and waits for its echo, until `deadline` and at
// most 100 ms (a device that answers the switch otherwise, as ArduPilot's
// simulators answer any GIA with attitude, costs no more): the pushes the
// device sent before it come before it.
void switch_off(FrameLink& link, const Probe& p, std::uint64_t deadline) {
  link.send(p.off);
  deadline = std::min(deadline, link.now() + 100'000);
  const auto off = top::parse_exact(p.off);
  if (off.status != top::ParseStatus::frame) return;
  Received r;
  while (link.next(deadline, r))
    if (r.frame.ident_view() == off.frame.ident_view() && r.frame.control == off.frame.control &&
        r.frame.data() == off.frame.data())
      return;
}

}  // namespace

ProbeHeard probe_once(FrameLink& link, const Probe& p, std::uint64_t timeout_us) {
  link.send(p.bytes);
  const std::uint64_t deadline = link.now() + timeout_us;
  Received r;
  ProbeHeard heard = ProbeHeard::nothing;
  while (link.next(deadline, r)) {
    if (p.answered_by(r.frame)) {
      if (!p.off.empty()) switch_off(link, p, deadline);
      return ProbeHeard::answer;
    }
    heard = ProbeHeard::other;
  }
  return heard;
}

}  // namespace topconf
