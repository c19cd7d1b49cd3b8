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

bool probe_answered(FrameLink& link, const Probe& p, std::uint64_t timeout_us) {
  link.send(p.bytes);
  const std::uint64_t deadline = link.now() + timeout_us;
  Received r;
  while (link.next(deadline, r)) {
    const std::string_view id = r.frame.ident_view();
    if ((id == p.ident && (!p.control || r.frame.control == p.control)) || top::is_error_reply(id))
      return true;
  }
  return false;
}

}  // namespace topconf
