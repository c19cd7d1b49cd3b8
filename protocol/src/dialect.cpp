#include "top/dialect.hpp"

#include "top/decode.hpp"
#include "top/device.hpp"

namespace top {

Dialect dialect_from_frame(const Frame& f) noexcept {
  if (f.src == 'P' || f.dst == 'P') return Dialect::topotek;
  if (f.header == Header::ext8 || f.header == Header::ext16 || f.header == Header::tmp_quirk)
    return Dialect::topotek;
  std::string_view id = f.ident_view();
  const bool sky = find_command(Dialect::skydroid, id) != nullptr;
  const bool topo = find_command(Dialect::topotek, id) != nullptr;
  if (sky && !topo) return Dialect::skydroid;
  if (topo && !sky) return Dialect::topotek;
  return Dialect::unknown;
}

void DialectDetector::observe_port(std::uint16_t port) noexcept {
  Dialect d = dialect_from_port(port);
  if (d != Dialect::unknown) port_ = d;
}

void DialectDetector::observe(const Frame& f) noexcept {
  switch (dialect_from_frame(f)) {
    case Dialect::skydroid:
      ++votes_skydroid_;
      break;
    case Dialect::topotek:
      ++votes_topotek_;
      break;
    case Dialect::unknown:
      break;
  }
}

Role role_from_layout(Dialect dialect, const Frame& f) noexcept {
  const std::size_t n = f.data().size();
  bool request = false, response = false;
  for (Dialect d : {Dialect::skydroid, Dialect::topotek}) {
    if (dialect != Dialect::unknown && d != dialect) continue;
    const CommandSpec* cmd = find_command(d, f.ident_view());
    if (!cmd) continue;
    for (const FormSpec& form : cmd->forms) {
      if (form.control != f.control || n < form.min_length || n > form.max_length) continue;
      request |= form.role != Role::response;
      response |= form.role != Role::request;
    }
  }
  if (response && !request) return Role::response;
  if (request && !response) return Role::request;
  // A read in no request's layout of a device stream's push (the SkyDroid
  // GAC push, which the document writes #TPUGCrGAC, client first).
  if (response && f.control == 'r')
    for (Dialect d : {Dialect::skydroid, Dialect::topotek}) {
      if (dialect != Dialect::unknown && d != dialect) continue;
      const StreamSpec* st = stream_of(d, f.ident_view());
      if (st && st->sender == Sender::device) return Role::response;
    }
  return Role::any;
}

}  // namespace top
