#include "top/dialect.hpp"

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

}  // namespace top
