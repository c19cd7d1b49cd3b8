// Pairing: the requests of one conversation waiting for their responses.
// TOP frames carry no sequence number, so a response answers the newest
// pending request of its identifier sent the other way, preferring one
// whose data it echoes; an ERE answers the newest request to the device it
// speaks for that the device rejects, else the newest to it. Requests older than the timeout are
// unanswered. Answered requests are remembered a while, so that a copy of one (senders that send
// each frame several times) is not reported unanswered.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "capture/sink.hpp"
#include "session/events.hpp"
#include "top/detail/ring.hpp"
#include "top/device.hpp"

namespace topdump {

inline constexpr std::size_t kMaxPending = 256;  // per conversation

struct Route;

// A request waiting for its response.
struct Pending {
  std::int64_t ts;
  std::uint64_t n;  // its frame number
  Position pos;
  char ident[3];
  char control;
  char src, dst;
  std::string data;
  int dir;  // the direction it was sent in (0 or 1)
  Cause cause;
  const top::CommandSpec* command;  // as decoded (null: none)
  const Route* at;                  // the pair of ends it went between (session.hpp)
};

// A write its device takes without a reply (top::write_reply nothing): only
// an echo of it, a reply of its own control, answers it.
inline bool takes_only_an_echo(const Pending& p) noexcept {
  return p.control == 'w' && p.command && top::write_reply(*p.command) == top::WriteReply::nothing;
}

inline bool same_ident(const char a[3], std::string_view b) noexcept {
  return b.size() == 3 && a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

class Pairing {
 public:
  // The pending request a response answers: its index, and whether the
  // response carries the request's data.
  struct Match {
    std::size_t index;
    bool echoed;
  };

  std::size_t size() const noexcept { return pending_.size(); }
  bool empty() const noexcept { return pending_.empty(); }
  const Pending& operator[](std::size_t i) const { return pending_[i]; }
  const Pending& oldest() const { return pending_[0]; }
  // The time of the oldest pending request (kNoTime: none, or untimed), so
  // the timeout check of every frame reads one member.
  std::int64_t oldest_ts() const noexcept { return oldest_; }

  // How many requests of `ident` sent in `dir` may be pending: 0 means
  // none (most frames skip the scan on it), more is a hint only.
  std::uint32_t maybe_pending(const char ident[3], int dir) const noexcept {
    return keys_[key(ident, dir)];
  }
  // A request of `ident` sent in `dir` is pending.
  bool waiting(const char ident[3], int dir) const noexcept;

  // Adds a request: `fill` assigns every member of a reused slot.
  template <class Fill>
  void add(Fill&& fill) {
    Pending& p = pending_.push_back();
    fill(p);
    count(p, true);
    changed();
  }
  // The request a response of `ident` with `data`, sent in `dir` by
  // `src`, answers (`ere`: the response is an ERE), if any.
  std::optional<Match> match(std::string_view ident, std::string_view data, char control, char src,
                             int dir, bool ere) const;
  // The request at `index` was answered: it leaves, and is remembered.
  void answer(std::size_t index);
  // The oldest request leaves (unanswered, or pushed out by a newer one).
  void pop_oldest() {
    count(pending_.front(), false);
    pending_.pop_front();
    changed();
  }
  // Each request older than `timeout_us` at `now`, oldest first, goes to
  // `unanswered` and leaves.
  template <class F>
  void expire(std::int64_t now, std::int64_t timeout_us, F&& unanswered) {
    if (now == kNoTime) return;
    while (oldest_ != kNoTime && now - oldest_ > timeout_us) {
      unanswered(pending_.front());
      pop_oldest();
    }
  }
  // A request like `p` (identifier, control, addresses and data) was
  // answered within `window_us` of it: `p` is a copy of an answered one.
  bool copy_of_answered(const Pending& p, std::int64_t window_us) const;

 private:
  // A request that was answered, to recognise its copies.
  struct Answered {
    char ident[3] = {};
    char control = 0;
    char src = 0, dst = 0;
    std::string data;
    std::int64_t ts = kNoTime;  // of the request
  };
  // Pending requests per (identifier, direction), counted in 64 buckets by
  // a hash of the pair. Pairs that share a bucket only cost a scan that
  // finds nothing; the scan decides.
  static std::size_t key(const char ident[3], int direction) noexcept {
    const std::uint32_t k = static_cast<std::uint32_t>(static_cast<unsigned char>(ident[0])) |
                            static_cast<std::uint32_t>(static_cast<unsigned char>(ident[1])) << 8 |
                            static_cast<std::uint32_t>(static_cast<unsigned char>(ident[2])) << 16 |
                            static_cast<std::uint32_t>(direction) << 24;
    return (k * 0x9E3779B1u) >> 26;  // 64 buckets
  }
  void count(const Pending& p, bool add) noexcept {
    std::uint16_t& n = keys_[key(p.ident, p.dir)];
    n = static_cast<std::uint16_t>(add ? n + 1 : n - 1);
  }
  void changed() noexcept { oldest_ = pending_.empty() ? kNoTime : pending_.front().ts; }

  top::detail::Ring<Pending> pending_;
  std::array<std::uint16_t, 64> keys_{};
  static_assert(kMaxPending < 0xFFFF);
  std::int64_t oldest_ = kNoTime;
  std::array<Answered, 8> answered_{};
  std::size_t answered_next_ = 0;
};

// match() and answer() run for every response: inline, as they were in
// the session before Pairing was a class (docs/perf/decisions.md).
// One pass from the newest: the first request whose data the response
// echoes, else the newest of its identifier (ERE: the newest to the device
// it speaks for that the device rejects (top::rejection), else the newest to
// it). A request of the response's control (a read's answer is a read, a
// write's echo a write) goes first: a TRC write and a TRC read in flight
// together are each answered by their own (a real Topotek camera answers
// the read and takes the write silently: the read's "01" is no echo of
// a "01" write). Oldest-first would pair a reply to a request that was lost
// (never answered) instead of the retry it answers: the latency would be
// off by up to the timeout and the retry reported unanswered. Newest-first
// can only swap two identical requests in flight, whose latencies are alike.
inline std::optional<Pairing::Match> Pairing::match(std::string_view ident, std::string_view data,
                                                    char control, char src, int dir,
                                                    bool ere) const {
  if (!ere && maybe_pending(ident.data(), 1 - dir) == 0) return std::nullopt;
  constexpr std::size_t kNone = SIZE_MAX;
  std::size_t by_ident = kNone, other_control = kNone;
  for (std::size_t i = pending_.size(); i-- > 0;) {
    const Pending& p = pending_[i];
    if (p.dir == dir) continue;
    if (ere) {
      if (p.dst != src) continue;
      if (p.cause == Cause::invalid || p.cause == Cause::unsupported) return Match{i, false};
      if (by_ident == kNone) by_ident = i;
      continue;
    }
    if (!same_ident(p.ident, ident)) continue;
    if (p.control != control) {
      if (other_control == kNone && !takes_only_an_echo(p)) other_control = i;
      continue;
    }
    if (p.data == data) return Match{i, true};
    if (by_ident == kNone) by_ident = i;
  }
  if (by_ident != kNone) return Match{by_ident, false};
  if (other_control == kNone) return std::nullopt;
  return Match{other_control, pending_[other_control].data == data};
}

inline void Pairing::answer(std::size_t index) {
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

}  // namespace topdump
