// The conversation table (conversation_table.hpp): a conversation per
// transport and pair of ends, found through a small cache of recent
// lookups; and the session's use of it: evicted least recently used past
// the limit, closed at the end of the input.
#include <algorithm>
#include <cstring>

#include "capture/link.hpp"
#include "session.hpp"

namespace topdump {

// Flows recognised by content are remembered as long as conversations.
static_assert(kMaxContentFlows == kMaxConversations);

namespace {
bool endpoint_less(const Endpoint& x, const Endpoint& y) {
  if (x.family != y.family) return x.family < y.family;
  if (x.addr != y.addr) return x.addr < y.addr;
  if (x.port != y.port) return x.port < y.port;
  return x.name < y.name;
}

std::uint64_t one(const Endpoint& e) noexcept {
  if (e.family == 0) return std::hash<std::string>{}(e.name);
  std::uint64_t a, b;
  std::memcpy(&a, e.addr.data(), 8);
  std::memcpy(&b, e.addr.data() + 8, 8);
  return (a * 0x9E3779B97F4A7C15ull) ^ (b * 0xC2B2AE3D27D4EB4Full) ^ (std::uint64_t{e.port} << 1);
}
}  // namespace

std::size_t ConvKeyHash::operator()(const ConvKey& k) const noexcept {
  std::uint64_t h = one(k.a) * 31 + one(k.b) + static_cast<std::uint64_t>(k.t);
  return static_cast<std::size_t>(h ^ (h >> 29));
}

std::size_t ConversationTable::EndpointHash::operator()(const Endpoint& e) const noexcept {
  const std::uint64_t h = one(e);
  return static_cast<std::size_t>(h ^ (h >> 29));
}

const Conversation* ConversationTable::answered_elsewhere(const Conversation& c, const Route& D,
                                                          std::int64_t after, Endpoint& to) const {
  if (!indexed_) index_ends();
  const auto it = by_end_.find(D.dst);
  if (it == by_end_.end()) return nullptr;
  for (const Conversation* o : it->second) {
    if (o == &c || o->transport != c.transport) continue;
    for (const Direction& x : o->dir)
      if (x.src == D.dst && x.dst.family == D.src.family && x.dst.addr == D.src.addr &&
          x.sent_frame && x.last_frame_ts != kNoTime && x.last_frame_ts >= after) {
        to = x.dst;
        return o;
      }
  }
  return nullptr;
}

std::size_t ConversationTable::HostHash::operator()(
    const std::array<std::uint8_t, 16>& a) const noexcept {
  std::uint64_t x, y;
  std::memcpy(&x, a.data(), 8);
  std::memcpy(&y, a.data() + 8, 8);
  const std::uint64_t h = (x * 0x9E3779B97F4A7C15ull) ^ (y * 0xC2B2AE3D27D4EB4Full);
  return static_cast<std::size_t>(h ^ (h >> 29));
}

namespace {
bool same_host(const Endpoint& a, const Endpoint& b) noexcept {
  return a.family == b.family && a.addr == b.addr;
}
bool has(const std::vector<std::uint16_t>& v, std::uint16_t p) noexcept {
  return std::find(v.begin(), v.end(), p) != v.end();
}
}  // namespace

// A UDP conversation with one end on a device's served port, of a dialect
// whose devices answer the client's host (top::replies_reach_host), takes
// every later pair of ends between the two hosts: the client's other
// ports, and the device's replies from another port of its own.
void ConversationTable::register_link(Conversation& c) {
  if (c.transport != Transport::udp || c.device_dir < 0) return;
  const Direction& dev = c.dir[c.device_dir];
  if (!dev.src.family || top::port_role(dev.src.port) != top::PortRole::device) return;
  top::Dialect dialect = opts_.dialect;
  if (dialect == top::Dialect::unknown && opts_.model != top::Model::unknown)
    dialect = top::dialect_of(opts_.model);
  if (dialect == top::Dialect::unknown) dialect = top::dialect_from_port(dev.src.port);
  if (!top::replies_reach_host(dialect)) return;
  auto l = std::make_unique<HostLink>();
  l->device = dev.src;
  l->client_host = dev.dst;
  l->client_host.port = 0;
  l->dialect = dialect;
  for (const top::PortSpec& p : top::known_ports())
    if (p.client && !p.tcp && p.dialect == dialect) l->client_port = p.port;
  HostLink::note_port(l->client_ports, dev.dst.port);
  c.link = std::move(l);
  links_[dev.src.addr].push_back(&c);
}

void ConversationTable::forget_link(Conversation& c) {
  if (!c.link) return;
  for (const auto& r : c.link->routes) {
    ConvKey k{Transport::udp, r->src, r->dst};
    if (endpoint_less(r->dst, r->src)) std::swap(k.a, k.b);
    routes_.erase(k);
  }
  if (auto at = links_.find(c.link->device.addr); at != links_.end()) {
    std::erase(at->second, &c);
    if (at->second.empty()) links_.erase(at);
  }
}

Conversation* ConversationTable::link_of(const Endpoint& src, const Endpoint& dst,
                                         const Route*& r) {
  if (links_.empty() || !src.family || !dst.family) return nullptr;
  // The device's end is on one of the two hosts; its conversation with the
  // other host decides.
  for (const bool from_device : {true, false}) {
    const Endpoint& dev = from_device ? src : dst;
    const Endpoint& cli = from_device ? dst : src;
    const auto at = links_.find(dev.addr);
    if (at == links_.end()) continue;
    for (Conversation* c : at->second) {
      HostLink& l = *c->link;
      if (!same_host(l.device, dev) || !same_host(l.client_host, cli)) continue;
      if (!from_device) {
        // a client port of the host writing to the device's served port
        if (dev.port != l.device.port) continue;
        HostLink::note_port(l.client_ports, cli.port);
      } else if (dev.port != l.device.port) {
        // the device writing from another port: an ephemeral one (a port of
        // the port table is another device's or a client's); on one host
        // (loopback) only to a port the client used or the dialect's client
        // port, and never from a port the client writes from
        if (top::is_top_port(dev.port)) continue;
        const bool one_host = same_host(dev, cli);
        if (one_host && !has(l.client_ports, cli.port) && cli.port != l.client_port) continue;
        if (one_host && has(l.client_ports, dev.port)) continue;
        HostLink::note_port(l.reply_ports, dev.port);
      }
      auto route = std::make_unique<Route>();
      route->src = src;
      route->dst = dst;
      route->from = src.text();
      route->to = dst.text();
      route->dir = from_device ? c->device_dir : 1 - c->device_dir;
      r = route.get();
      ConvKey k{Transport::udp, src, dst};
      if (endpoint_less(dst, src)) std::swap(k.a, k.b);
      routes_.emplace(std::move(k), std::make_pair(c, route.get()));
      l.routes.push_back(std::move(route));
      return c;
    }
  }
  return nullptr;
}

Conversation* ConversationTable::find_slow(Transport t, const Endpoint& src, const Endpoint& dst,
                                           const Route*& r) {
  ConvKey k{t, src, dst};
  if (endpoint_less(dst, src)) std::swap(k.a, k.b);
  if (auto it = convs_.find(k); it != convs_.end()) {
    Conversation& c = *it->second;
    c.last_used = ++clock_;
    r = (c.dir[0].src == src && c.dir[0].dst == dst) ? &c.dir[0] : &c.dir[1];
    return &c;
  }
  if (t != Transport::udp) return nullptr;
  if (const auto at = routes_.find(k); at != routes_.end()) {
    Conversation& c = *at->second.first;
    c.last_used = ++clock_;
    r = at->second.second;
    // the same pair the other way (a client port the device answers)
    if (!(r->src == src)) {
      for (const auto& x : c.link->routes)
        if (x->src == src && x->dst == dst) {
          r = x.get();
          return &c;
        }
      const Route* back = r;
      auto route = std::make_unique<Route>();
      route->src = src;
      route->dst = dst;
      route->from = back->to;
      route->to = back->from;
      route->dir = 1 - back->dir;
      r = route.get();
      c.link->routes.push_back(std::move(route));
    }
    return &c;
  }
  if (Conversation* c = link_of(src, dst, r)) {
    c->last_used = ++clock_;
    return c;
  }
  return nullptr;
}

Conversation& ConversationTable::add(Transport t, const Endpoint& src, const Endpoint& dst,
                                     const Route*& r) {
  ConvKey k{t, src, dst};
  if (endpoint_less(dst, src)) std::swap(k.a, k.b);
  auto c = std::make_unique<Conversation>();
  c->id = next_id_++;
  c->transport = t;
  c->dir[0].src = src;
  c->dir[0].dst = dst;
  c->dir[0].from = src.text();
  c->dir[0].to = dst.text();
  c->dir[0].dir = 0;
  c->dir[1].src = dst;
  c->dir[1].dst = src;
  c->dir[1].from = c->dir[0].to;
  c->dir[1].to = c->dir[0].from;
  c->dir[1].dir = 1;
  c->dir[0].tcp = TcpReassembly(opts_.max_tcp_held);
  c->dir[1].tcp = TcpReassembly(opts_.max_tcp_held);
  if (opts_.dialect != top::Dialect::unknown) c->det.force(opts_.dialect);
  if (opts_.model != top::Model::unknown) c->det.force(top::dialect_of(opts_.model));
  if (src.family) c->det.observe_port(src.port);
  if (dst.family) c->det.observe_port(dst.port);
  if (src.family && dst.family) {
    const bool s_dev = top::port_role(src.port) == top::PortRole::device;
    const bool d_dev = top::port_role(dst.port) == top::PortRole::device;
    if (s_dev != d_dev) c->device_dir = s_dev ? 0 : 1;
  }
  c->st.id = c->id;
  c->st.transport = t;
  if (indexed_ && src.family && dst.family)
    for (const Endpoint* e : {&src, &dst}) by_end_[*e].push_back(c.get());
  register_link(*c);
  Conversation& made = *convs_.emplace(std::move(k), std::move(c)).first->second;
  made.last_used = ++clock_;
  r = &made.dir[0];
  cache_[cache_slot(t, src, dst)] = CacheSlot{&made, r};
  return made;
}

ConversationTable::~ConversationTable() = default;

Conversation& ConversationTable::least_recent() const {
  auto victim = convs_.begin();
  for (auto it = convs_.begin(); it != convs_.end(); ++it)
    if (it->second->last_used < victim->second->last_used) victim = it;
  return *victim->second;
}

void ConversationTable::remove(Conversation& c) {
  cache_.fill(CacheSlot{});
  for (const Endpoint* e : {&c.dir[0].src, &c.dir[0].dst})
    if (auto at = by_end_.find(*e); at != by_end_.end()) {
      std::erase(at->second, &c);
      if (at->second.empty()) by_end_.erase(at);
    }
  forget_link(c);
  ConvKey k{c.transport, c.dir[0].src, c.dir[0].dst};
  if (endpoint_less(k.b, k.a)) std::swap(k.a, k.b);
  convs_.erase(k);
}

std::vector<Conversation*> ConversationTable::by_id() const {
  std::vector<Conversation*> order;
  for (const auto& [k, c] : convs_) order.push_back(c.get());
  std::sort(order.begin(), order.end(),
            [](const Conversation* a, const Conversation* b) { return a->id < b->id; });
  return order;
}

void ConversationTable::index_ends() const {
  for (Conversation* c : by_id())
    if (c->dir[0].src.family && c->dir[0].dst.family)
      for (const Endpoint* e : {&c->dir[0].src, &c->dir[0].dst}) by_end_[*e].push_back(c);
  indexed_ = true;
}

void ConversationTable::clear() {
  cache_.fill(CacheSlot{});
  by_end_.clear();
  indexed_ = false;
  routes_.clear();
  links_.clear();
  convs_.clear();
}

Analyzer::Impl::Impl(Analyzer& a, const AnalyzerOptions& o)
    : A(a), table(TableOptions{o.dialect, o.model, o.max_tcp_held}) {}

void Analyzer::Impl::evict() {
  Conversation& c = table.least_recent();
  std::string msg = "more than " + std::to_string(A.opts_.max_conversations) +
                    " live conversations: closed conversation " + std::to_string(c.id) + " (" +
                    c.dir[0].from + " <> " + c.dir[0].to + ")";
  close(c, kNoTime);
  note_event(kNoTime, Position{}, c.transport, nullptr, nullptr, nullptr,
             Note{ACode::conversation_limit, default_severity(ACode::conversation_limit), msg, 0},
             ++limit_notes <= 10);
  table.remove(c);
}

void Analyzer::Impl::close(Conversation& c, std::int64_t ts) {
  for (int d = 0; d < 2; ++d) {
    Direction& D = c.dir[d];
    TcpSide side(*this, c, d);
    D.tcp.finish(ts, side);
    D.dec.finish();
    drain_stream(c, d, ts);
  }
  // After -c the input was cut short: what is pending may yet be answered.
  while (!c.pairing.empty()) {
    if (!A.done_) unanswered(c, c.pairing.oldest(), true);
    c.pairing.pop_oldest();
  }
  emit_silence(c);
  link_notes(c);
  for (const StreamStat& s : c.st.streams) check_stream(c, s);
  c.watch.finish(last_ts(c));
  c.watch.verdicts([&](diag::Found f) { diagnose(c, std::move(f)); },
                   c.transport == Transport::serial, c.dir[0].sent_frame || c.dir[1].sent_frame);
  c.st.dialect = c.det.current();
  if (A.filtering_) {
    // The statistics hold what the filter selected: conversations with a
    // selected frame, and the streams of the identifiers selected.
    if (c.st.frames == 0) return;
    std::erase_if(c.st.streams, [&](const StreamStat& s) {
      return !A.filter_.selects_ident(s.ident) && !A.filter_.selects_ident(s.asked_by);
    });
  }
  // The statistics take the conversation's: it is removed after its close.
  if (A.stats_.conversations.size() < kMaxStatsConversations) {
    c.st.a = c.dir[0].from;
    c.st.b = c.dir[0].to;
    A.stats_.conversations.push_back(std::move(c.st));
  } else
    ++A.stats_.conversations_dropped;
}

void Analyzer::finish() {
  for (Conversation* c : impl_->table.by_id()) impl_->close(*c, kNoTime);
  impl_->table.clear();
  std::sort(stats_.conversations.begin(), stats_.conversations.end(),
            [](const ConvStats& a, const ConvStats& b) { return a.id < b.id; });
}

}  // namespace topdump
