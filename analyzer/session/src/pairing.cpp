#include "session/pairing.hpp"

#include <algorithm>
#include <cstdlib>

namespace topdump {

bool Pairing::waiting(const char ident[3], int dir) const noexcept {
  if (maybe_pending(ident, dir) == 0) return false;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    const Pending& p = pending_[i];
    if (p.dir == dir && same_ident(p.ident, std::string_view(ident, 3))) return true;
  }
  return false;
}

bool Pairing::copy_of_answered(const Pending& p, std::int64_t window_us) const {
  if (p.ts == kNoTime) return false;
  for (const Answered& a : answered_)
    if (a.ts != kNoTime && same_ident(p.ident, std::string_view(a.ident, 3)) &&
        a.control == p.control && a.src == p.src && a.dst == p.dst && a.data == p.data &&
        std::llabs(a.ts - p.ts) <= std::max<std::int64_t>(window_us, 0))
      return true;
  return false;
}

}  // namespace topdump
