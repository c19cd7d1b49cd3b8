// The session's conversation table: a conversation per transport and pair
// of ends, found through a small cache of recent lookups; a UDP
// conversation of a device that answers the client's host (HostLink) also
// takes every later pair of ends between the two hosts. The session decides
// when a conversation is made, evicted and closed (conversations.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <unordered_map>
#include <vector>

#include "session/conversation.hpp"

namespace topdump {

// The table's key: a transport and both ends, the lesser first.
struct ConvKey {
  Transport t;
  Endpoint a, b;  // a < b
  bool operator==(const ConvKey&) const = default;
};

struct ConvKeyHash {
  std::size_t operator()(const ConvKey& k) const noexcept;
};

// How the table makes a conversation (AnalyzerOptions').
struct TableOptions {
  top::Dialect dialect = top::Dialect::unknown;  // forced on every conversation
  top::Model model = top::Model::unknown;
  std::size_t max_tcp_held = 0;
};

class ConversationTable {
 public:
  explicit ConversationTable(TableOptions o) : opts_(o) {}
  ConversationTable(const ConversationTable&) = delete;
  ConversationTable& operator=(const ConversationTable&) = delete;
  ~ConversationTable();

  // The conversation of a record from `src` to `dst` and the pair of ends it
  // went between (r: its direction r->dir, its texts r->from, r->to), or
  // null when the table has none.
  Conversation* find(Transport t, const Endpoint& src, const Endpoint& dst, const Route*& r) {
    CacheSlot& slot = cache_[cache_slot(t, src, dst)];
    if (slot.c && slot.c->transport == t && slot.r->src == src && slot.r->dst == dst) {
      slot.c->last_used = ++clock_;
      r = slot.r;
      return slot.c;
    }
    Conversation* c = find_slow(t, src, dst, r);
    if (c) slot = CacheSlot{c, r};
    return c;
  }
  // A new conversation of the pair (find() found none).
  Conversation& add(Transport t, const Endpoint& src, const Endpoint& dst, const Route*& r);
  std::size_t size() const noexcept { return convs_.size(); }
  Conversation& least_recent() const;
  // Forgets a conversation (its ends, its HostLink's pairs) and frees it.
  void remove(Conversation& c);
  // Every conversation, in the table's order / by id.
  template <class F>
  void each(F&& f) const {
    for (const auto& [k, c] : convs_) f(*c);
  }
  std::vector<Conversation*> by_id() const;
  void clear();
  // The conversation other than `c` in which the device end of direction D
  // of `c` sent a frame at or after `after` to another port of D's source
  // host, and that port's end; nullptr when none (asked only when a request
  // goes unanswered, to tell a silent device from one that answers to
  // another port of the client's host: Topotek V1.1.3, to UDP 9004).
  const Conversation* answered_elsewhere(const Conversation& c, const Route& D, std::int64_t after,
                                         Endpoint& to) const;

 private:
  Conversation* find_slow(Transport t, const Endpoint& src, const Endpoint& dst, const Route*& r);
  // The conversation a new pair of UDP ends belongs to through a HostLink
  // (and the Route it takes for the pair), or nullptr.
  Conversation* link_of(const Endpoint& src, const Endpoint& dst, const Route*& r);
  void register_link(Conversation& c);
  void forget_link(Conversation& c);
  static std::size_t cache_slot(Transport t, const Endpoint& src, const Endpoint& dst) noexcept {
    std::uint64_t h = static_cast<std::uint64_t>(t) + 1;
    for (const Endpoint* e : {&src, &dst}) {
      std::uint64_t a = 0, b = 0;
      std::memcpy(&a, e->addr.data(), 8);
      std::memcpy(&b, e->addr.data() + 8, 8);
      h = (h ^ a ^ (b >> 1) ^ (std::uint64_t{e->port} << 7) ^ e->name.size()) *
          0x9E3779B97F4A7C15ull;
    }
    return static_cast<std::size_t>(h >> 58);  // 64 slots
  }

  TableOptions opts_;
  std::unordered_map<ConvKey, std::unique_ptr<Conversation>, ConvKeyHash> convs_;
  std::uint64_t next_id_ = 1;
  std::uint64_t clock_ = 0;
  // Recently used (transport, src, dst) -> conversation and pair of ends, so
  // most records skip building and hashing a ConvKey. Checked on every hit;
  // cleared when a conversation is removed.
  struct CacheSlot {
    Conversation* c = nullptr;
    const Route* r = nullptr;  // the pair, a conversation's own or a HostLink's
  };
  std::array<CacheSlot, 64> cache_{};
  // The conversations of devices that answer the client's host, by the
  // device's address: asked only for a pair of ends no conversation has.
  struct HostHash {
    std::size_t operator()(const std::array<std::uint8_t, 16>& a) const noexcept;
  };
  std::unordered_map<std::array<std::uint8_t, 16>, std::vector<Conversation*>, HostHash> links_;
  // The pairs HostLinks took, to find them again (the key of each pair).
  std::unordered_map<ConvKey, std::pair<Conversation*, const Route*>, ConvKeyHash> routes_;
  // The network conversations of each end (both ends of each), in the order
  // they were made: built at the first answered_elsewhere(), which few
  // captures ask, then kept (four heap blocks a conversation that the fuzz
  // targets paid per input: docs/perf/fuzz-speed.md, "Issue 48: the
  // per-conversation cost").
  struct EndpointHash {
    std::size_t operator()(const Endpoint& e) const noexcept;
  };
  void index_ends() const;
  mutable std::unordered_map<Endpoint, std::vector<Conversation*>, EndpointHash> by_end_;
  mutable bool indexed_ = false;
};

}  // namespace topdump
