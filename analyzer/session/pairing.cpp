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

// One pass from the newest: the first request whose data the response
// echoes, else the newest of its identifier (ERE: the newest to the device
// it speaks for). Oldest-first would pair a reply to a request that was lost
// (never answered) instead of the retry it answers: the latency would be
// off by up to the timeout and the retry reported unanswered. Newest-first
// can only swap two identical requests in flight, whose latencies are alike.
std::optional<Pairing::Match> Pairing::match(std::string_view ident, std::string_view data,
                                             char src, int dir, bool ere) const {
  if (!ere && maybe_pending(ident.data(), 1 - dir) == 0) return std::nullopt;
  constexpr std::size_t kNone = SIZE_MAX;
  std::size_t by_ident = kNone;
  for (std::size_t i = pending_.size(); i-- > 0;) {
    const Pending& p = pending_[i];
    if (p.dir == dir) continue;
    if (ere) {
      if (p.dst == src) {
        by_ident = i;
        break;
      }
      continue;
    }
    if (!same_ident(p.ident, ident)) continue;
    if (p.data == data) return Match{i, true};
    if (by_ident == kNone) by_ident = i;
  }
  if (by_ident == kNone) return std::nullopt;
  return Match{by_ident, false};
}

void Pairing::answer(std::size_t index) {
  const Pending& m = pending_[index];
  Answered& a = answered_[answered_next_++ % answered_.size()];
  std::memcpy(a.ident, m.ident, 3);
  a.control = m.control;
  a.src = m.src;
  a.dst = m.dst;
  a.data = m.data;
  a.ts = m.ts;
  count(m, false);
  pending_.erase(index);
  changed();
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
