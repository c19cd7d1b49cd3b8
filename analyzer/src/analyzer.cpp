#include "analyzer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "escape.hpp"
#include "render.hpp"
#include "ring.hpp"

namespace topdump {

constexpr std::string_view kTransport[] = {"udp", "tcp", "serial"};
static_assert(std::size(kTransport) == static_cast<std::size_t>(Transport::serial) + 1);

std::string_view to_string(Transport t) noexcept {
  const auto i = static_cast<std::size_t>(t);
  return i < std::size(kTransport) ? kTransport[i] : "?";
}

bool looks_like_top(std::string_view p) noexcept {
  for (std::size_t i = p.find('#'); i != std::string_view::npos; i = p.find('#', i + 1)) {
    if (i + 2 < p.size() && (p[i + 1] == 'T' || p[i + 1] == 't') &&
        (p[i + 2] == 'P' || p[i + 2] == 'p'))
      return true;
    if (p.substr(i, 9) == "#PDP16TMP") return true;
  }
  return false;
}

top::Severity FrameEvent::worst() const noexcept {
  top::Severity w = entry ? entry->worst : top::Severity::info;
  for (const Note& x : notes)
    if (x.severity > w) w = x.severity;
  return w;
}

// ---------------------------------------------------------------------------
// Latency: log buckets of 1% width from 1 us.

std::size_t Latency::bucket_exact(std::int64_t us) {
  if (us <= 1) return 0;
  return static_cast<std::size_t>(std::log(static_cast<double>(us)) / std::log(1.01)) + 1;
}

std::size_t Latency::bucket(std::int64_t us) {
  // A log per sample is a fair part of the per-frame cost, and so was a
  // 128 KiB table of the buckets below 65.536 ms (its lines missed the
  // cache). Below 256 us a small table; up to 65.536 ms the range of each
  // power of two is cut in 64 slices, each under 1.6% wide, so at most two
  // 1% buckets begin inside a slice: its first bucket and where the next two
  // begin. The same buckets as bucket_exact (tested for every value).
  struct Slice {
    std::uint16_t base;
    std::uint16_t t1, t2;  // offsets in the slice where base + 1 and base + 2 begin
  };
  struct Tables {
    std::array<std::uint16_t, 256> small{};
    std::array<std::array<Slice, 64>, 8> slices{};  // powers 2^8 .. 2^15
  };
  static const Tables kTables = [] {
    Tables t;
    for (std::int64_t x = 0; x < 256; ++x)
      t.small[static_cast<std::size_t>(x)] = static_cast<std::uint16_t>(bucket_exact(x));
    for (int k = 8; k < 16; ++k)
      for (std::int64_t j = 0; j < 64; ++j) {
        const std::int64_t width = std::int64_t{1} << (k - 6);
        const std::int64_t lo = (std::int64_t{1} << k) + j * width;
        Slice& s = t.slices[static_cast<std::size_t>(k - 8)][static_cast<std::size_t>(j)];
        const std::size_t base = bucket_exact(lo);
        s.base = static_cast<std::uint16_t>(base);
        // the first offset in [1, width) whose bucket is past b (width: none),
        // by bisection (the buckets rise with the value): a tenth of the
        // logarithms of a scan, at every start of topdump
        auto first_past = [&](std::size_t b) {
          std::int64_t a = 1, z = width;
          while (a < z) {
            const std::int64_t m = a + (z - a) / 2;
            if (bucket_exact(lo + m) > b)
              z = m;
            else
              a = m + 1;
          }
          return static_cast<std::uint16_t>(a);
        };
        s.t1 = first_past(base);
        s.t2 = first_past(base + 1);
      }
    return t;
  }();
  if (us < 256) return us <= 1 ? 0 : kTables.small[static_cast<std::size_t>(us)];
  if (us >= 65536) return bucket_exact(us);
  const auto x = static_cast<std::uint32_t>(us);
  const int k = 31 - std::countl_zero(x);  // 8 .. 15
  const std::uint32_t at = x - (std::uint32_t{1} << k);
  const std::uint32_t shift = static_cast<std::uint32_t>(k - 6);
  const Slice& s = kTables.slices[static_cast<std::size_t>(k - 8)][at >> shift];
  const std::uint32_t in = at & ((std::uint32_t{1} << shift) - 1);
  return std::size_t{s.base} + (in >= s.t1) + (in >= s.t2);
}
std::int64_t Latency::bucket_value(std::size_t b) {
  if (b == 0) return 1;
  return static_cast<std::int64_t>(std::llround(std::pow(1.01, static_cast<double>(b))));
}
void Latency::add(std::int64_t us) {
  if (us < 0) us = 0;
  std::size_t b = std::min<std::size_t>(bucket(us), 4000);
  if (buckets_.size() <= b) buckets_.resize(b + 1, 0);
  ++buckets_[b];
  if (count_ < kExact) exact_.push_back(us);
  if (count_ == 0 || us < min_) min_ = us;
  if (count_ == 0 || us > max_) max_ = us;
  ++count_;
}
std::int64_t Latency::quantile(double q) const {
  if (count_ == 0) return 0;
  auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_)));
  if (rank == 0) rank = 1;
  if (count_ <= kExact) {
    std::vector<std::int64_t> v = exact_;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(rank - 1), v.end());
    return v[rank - 1];
  }
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < buckets_.size(); ++b) {
    seen += buckets_[b];
    if (seen >= rank) return std::clamp(bucket_value(b), min_, max_);
  }
  return max_;
}

double StreamStat::measured_hz() const {
  if (frames < 2 || first == kNoTime || last <= first) return 0;
  return static_cast<double>(frames - 1) * 1e6 / static_cast<double>(last - first);
}

// ---------------------------------------------------------------------------
// Filter

namespace {
std::string_view host_of(std::string_view ep) {
  if (!ep.empty() && ep.front() == '[') {
    auto e = ep.find(']');
    return e == std::string_view::npos ? ep : ep.substr(1, e - 1);
  }
  auto c = ep.rfind(':');
  return c == std::string_view::npos ? ep : ep.substr(0, c);
}
bool endpoint_matches(std::string_view want, std::string_view ep) {
  return want == ep || want == host_of(ep);
}
}  // namespace

bool Filter::selects_time(std::int64_t ts) const {
  if (ts == kNoTime) return from == kNoTime && to == kNoTime;
  if (from != kNoTime && ts < from) return false;
  if (to != kNoTime && ts > to) return false;
  return true;
}

bool Filter::active() const {
  return !idents.empty() || !addrs.empty() || severity_set || from != kNoTime || to != kNoTime;
}

bool Filter::selects(const FrameEvent& e) const {
  const top::Frame& f = *e.entry->frame;
  if (!idents.empty() && std::find(idents.begin(), idents.end(), f.ident_view()) == idents.end())
    return false;
  if (!addrs.empty()) {
    bool any = false;
    for (const std::string& a : addrs) {
      if (a.size() == 1 ? (f.src == a[0] || f.dst == a[0])
                        : (endpoint_matches(a, *e.from) || endpoint_matches(a, *e.to))) {
        any = true;
        break;
      }
    }
    if (!any) return false;
  }
  if (severity_set && e.worst() < min_severity) return false;
  return selects_time(e.ts);
}

// ---------------------------------------------------------------------------
// Conversations

namespace {

struct Seg {
  std::uint64_t stream_off;
  std::uint64_t record;
  std::uint64_t rec_off;
  std::int64_t ts;
};

struct Held {
  std::string bytes;
  std::uint64_t record;
  std::uint32_t offset;
  std::int64_t ts;
};

// Why a request may go unanswered, as far as the capture shows.
enum class Cause : std::uint8_t {
  none,
  bad_checksum,  // devices drop frames they cannot trust
  uart_source,   // Topotek: source U over the network, answers go to the UART
  unsupported,   // not in the catalog, or not on the model
  invalid        // a wrong length or value: Topotek ignores it, SkyDroid answers ERE
};

struct Pending {
  std::int64_t ts;
  std::uint64_t n;
  Position pos;
  char ident[3];
  char control;
  char src, dst;
  std::string data;
  int dir;
  Cause cause;
};

// A request that was answered, to recognise its copies.
struct Answered {
  char ident[3] = {};
  char control = 0;
  char src = 0, dst = 0;
  std::string data;
  std::int64_t ts = kNoTime;  // of the request
};

// Requests that went unanswered while the device said nothing: reported as
// one finding for the stretch.
struct Silence {
  std::uint64_t count = 0;
  std::uint64_t first_n = 0, last_n = 0;
  std::int64_t first_ts = kNoTime, last_ts = kNoTime;
  Position pos;
  int dir = 0;
  std::string idents;  // "GAY, VER, PTZ"
  std::string single;  // the message when the stretch holds one request
};

}  // namespace

struct Direction {
  Endpoint src, dst;
  std::string from, to;
  top::StreamDecoder dec;
  std::deque<Seg> segs;
  std::uint64_t base = 0;  // stream offset of the decoder's offset 0
  std::uint64_t last_record = 0;
  std::uint32_t index = 0;
  // TCP
  bool tcp_init = false;
  std::uint32_t next_seq = 0;
  std::map<std::uint32_t, Held> ooo;  // keyed by seq - next_seq at insertion time ordering
  std::size_t held = 0;
  std::string tail;  // last delivered bytes, for overlap checks
  // repeats
  std::string last_req;
  std::int64_t last_req_ts = kNoTime;
  std::int64_t last_frame_ts = kNoTime;  // the last frame this direction sent
  bool sent_frame = false;
};

struct Conversation {
  std::uint64_t id = 0;
  Transport transport{};
  Direction dir[2];
  bool has_dir1 = false;
  // The direction the device sends in (-1: not known yet): from the ports
  // (a well-known device port at one end), else from the first frame that
  // only a device sends (addressed to a client, or answering a request), or
  // the first stream switch (GAA, GIA, FAE) a client sends.
  int device_dir = -1;
  std::array<Answered, 8> answered{};
  std::size_t answered_next = 0;
  Silence silence;
  top::DialectDetector det;
  std::uint32_t observed = 0;
  Ring<Pending> pending;
  // How many pending requests per (identifier, direction), counted in 64
  // buckets by a hash of the pair: a frame whose bucket is empty has no
  // request to answer and skips the scan of `pending` (stream frames,
  // requests). Pairs that share a bucket only cost a scan that finds
  // nothing; the scan decides.
  std::array<std::uint16_t, 64> pending_keys{};
  static_assert(kMaxPending < 0xFFFF);

  static std::size_t key(const char ident[3], int direction) noexcept {
    const std::uint32_t k = static_cast<std::uint32_t>(static_cast<unsigned char>(ident[0])) |
                            static_cast<std::uint32_t>(static_cast<unsigned char>(ident[1])) << 8 |
                            static_cast<std::uint32_t>(static_cast<unsigned char>(ident[2])) << 16 |
                            static_cast<std::uint32_t>(direction) << 24;
    return (k * 0x9E3779B1u) >> 26;  // 64 buckets
  }
  std::uint32_t pending_count(const char ident[3], int direction) const noexcept {
    return pending_keys[key(ident, direction)];
  }
  void count_pending(const Pending& p, bool add) noexcept {
    std::uint16_t& n = pending_keys[key(p.ident, p.dir)];
    n = static_cast<std::uint16_t>(add ? n + 1 : n - 1);
  }
  std::uint64_t last_used = 0;
  // The time of the oldest pending request (kNoTime: none, or untimed), so
  // the timeout check of every frame reads one member.
  std::int64_t oldest = kNoTime;

  void pending_changed() noexcept { oldest = pending.empty() ? kNoTime : pending.front().ts; }
  void pop_pending() {
    count_pending(pending.front(), false);
    pending.pop_front();
    pending_changed();
  }
  void erase_pending(std::size_t i) {
    count_pending(pending[i], false);
    pending.erase(i);
    pending_changed();
  }
  ConvStats st;
};

namespace {

struct ConvKey {
  Transport t;
  Endpoint a, b;  // a < b
  bool operator==(const ConvKey&) const = default;
};

bool endpoint_less(const Endpoint& x, const Endpoint& y) {
  if (x.family != y.family) return x.family < y.family;
  if (x.addr != y.addr) return x.addr < y.addr;
  if (x.port != y.port) return x.port < y.port;
  return x.name < y.name;
}

struct ConvKeyHash {
  std::size_t operator()(const ConvKey& k) const noexcept {
    auto one = [](const Endpoint& e) -> std::uint64_t {
      if (e.family == 0) return std::hash<std::string>{}(e.name);
      std::uint64_t a, b;
      std::memcpy(&a, e.addr.data(), 8);
      std::memcpy(&b, e.addr.data() + 8, 8);
      return (a * 0x9E3779B97F4A7C15ull) ^ (b * 0xC2B2AE3D27D4EB4Full) ^
             (std::uint64_t{e.port} << 1);
    };
    std::uint64_t h = one(k.a) * 31 + one(k.b) + static_cast<std::uint64_t>(k.t);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

}  // namespace

struct Analyzer::Impl {
  Analyzer& A;
  std::unordered_map<ConvKey, std::unique_ptr<Conversation>, ConvKeyHash> convs;
  std::uint64_t next_conv = 1;
  std::uint64_t clock = 0;
  DecodedEntry current;
  top::DecodeCache decode_cache;  // used without detail (topdump stats)
  top::ParseResult scratch;       // the one-frame datagram path parses into this
  std::unordered_map<std::uint32_t, std::uint64_t> idents;  // other identifiers
  // Frames per identifier of three [0-9A-Z] characters (every valid one): a
  // flat table indexed by top::ident_index.
  std::vector<std::uint64_t> ident_table = std::vector<std::uint64_t>(top::ident_slots);

  void count_ident(const char id[3]) {
    if (const int i = top::ident_index(id); i >= 0)
      ++ident_table[static_cast<std::size_t>(i)];
    else
      ++idents[pack(std::string_view(id, 3))];
  }
  std::array<std::uint64_t, top::finding_code_count> codes{};
  std::array<std::uint64_t, acode_count> acodes{};
  // Latency per identifier: a capture pairs a handful of identifiers, so a
  // linear search of their keys beats hashing (a division per reply).
  std::vector<std::uint32_t> latency_keys;
  std::deque<Latency> latency;  // latency[i] is latency_keys[i]'s
  // The last index found for each of 64 hashed slots: most replies find
  // their identifier's table there without a search (whose exit, at a
  // different place for each identifier, mispredicted).
  std::array<std::uint32_t, 64> latency_hint{};  // 1 + index into latency, 0: none
  Latency& latency_of(std::uint32_t key) {
    std::uint32_t& hint = latency_hint[(key * 0x9E3779B1u) >> 26];
    if (hint != 0 && latency_keys[hint - 1] == key) return latency[hint - 1];
    std::size_t i = 0;
    while (i < latency_keys.size() && latency_keys[i] != key) ++i;
    if (i == latency_keys.size()) {
      latency_keys.push_back(key);
      latency.emplace_back();
    }
    hint = static_cast<std::uint32_t>(i + 1);
    return latency[i];
  }
  std::uint64_t limit_notes = 0;

  // A finding's or note's message, built only when events are described
  // (AnalyzerOptions::detail); topdump stats counts them without text.
  template <class Make>
  std::string message(Make&& make) const {
    return A.opts_.detail ? std::string(make()) : std::string();
  }

  explicit Impl(Analyzer& a) : A(a) {}

  // Recently used (transport, src, dst) -> conversation and direction, so
  // most records skip building and hashing a ConvKey. Checked on every hit;
  // cleared when a conversation is closed.
  struct CacheSlot {
    Conversation* c = nullptr;
    int d = 0;
  };
  std::array<CacheSlot, 64> cache{};

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

  Conversation& get(Transport t, const Endpoint& src, const Endpoint& dst, int& d) {
    CacheSlot& slot = cache[cache_slot(t, src, dst)];
    if (slot.c && slot.c->transport == t && slot.c->dir[slot.d].src == src &&
        slot.c->dir[slot.d].dst == dst) {
      slot.c->last_used = ++clock;
      d = slot.d;
      return *slot.c;
    }
    Conversation& c = get_slow(t, src, dst, d);
    slot.c = &c;
    slot.d = d;
    return c;
  }

  Conversation& get_slow(Transport t, const Endpoint& src, const Endpoint& dst, int& d) {
    ConvKey k{t, src, dst};
    if (endpoint_less(dst, src)) std::swap(k.a, k.b);
    auto it = convs.find(k);
    if (it == convs.end()) {
      if (convs.size() >= A.opts_.max_conversations) evict();
      auto c = std::make_unique<Conversation>();
      c->id = next_conv++;
      c->transport = t;
      c->dir[0].src = src;
      c->dir[0].dst = dst;
      c->dir[0].from = src.text();
      c->dir[0].to = dst.text();
      c->dir[1].src = dst;
      c->dir[1].dst = src;
      c->dir[1].from = c->dir[0].to;
      c->dir[1].to = c->dir[0].from;
      if (A.opts_.dialect != top::Dialect::unknown) c->det.force(A.opts_.dialect);
      if (A.opts_.model != top::Model::unknown) c->det.force(top::dialect_of(A.opts_.model));
      if (src.family) c->det.observe_port(src.port);
      if (dst.family) c->det.observe_port(dst.port);
      if (src.family && dst.family) {
        const bool s_dev = top::port_role(src.port) == top::PortRole::device;
        const bool d_dev = top::port_role(dst.port) == top::PortRole::device;
        if (s_dev != d_dev) c->device_dir = s_dev ? 0 : 1;
      }
      c->st.id = c->id;
      c->st.a = c->dir[0].from;
      c->st.b = c->dir[0].to;
      c->st.transport = t;
      it = convs.emplace(std::move(k), std::move(c)).first;
    }
    Conversation& c = *it->second;
    c.last_used = ++clock;
    d = (c.dir[0].src == src && c.dir[0].dst == dst) ? 0 : 1;
    return c;
  }

  void evict() {
    auto victim = convs.begin();
    for (auto it = convs.begin(); it != convs.end(); ++it)
      if (it->second->last_used < victim->second->last_used) victim = it;
    Conversation& c = *victim->second;
    std::string msg = "more than " + std::to_string(A.opts_.max_conversations) +
                      " live conversations: closed conversation " + std::to_string(c.id) + " (" +
                      c.dir[0].from + " <> " + c.dir[0].to + ")";
    close(c, kNoTime);
    cache.fill(CacheSlot{});
    note_event(kNoTime, Position{}, c.transport, nullptr, nullptr, nullptr,
               Note{ACode::conversation_limit, default_severity(ACode::conversation_limit), msg, 0},
               ++limit_notes <= 10);
    convs.erase(victim);
  }

  void note_event(std::int64_t ts, Position pos, Transport t, const Conversation* c,
                  const std::string* from, const std::string* to, Note n, bool emit = true) {
    ++acodes[static_cast<std::size_t>(n.code)];
    if (n.severity > A.worst_) A.worst_ = n.severity;
    if (!emit) return;
    if (A.filter_.severity_set && n.severity < A.filter_.min_severity) return;
    if (!A.filter_.selects_time(ts) && ts != kNoTime) return;
    NoteEvent e;
    e.ts = ts;
    e.pos = pos;
    e.transport = t;
    e.conv = c;
    e.from = from;
    e.to = to;
    e.note = std::move(n);
    A.sink_.note(e);
  }

  // --- items out of a decoder ---------------------------------------------

  Position map_position(Direction& D, std::uint64_t off, std::uint64_t len,
                        std::uint64_t& stream_off, std::int64_t& ts) {
    while (D.segs.size() > 1 && D.segs[1].stream_off <= off) D.segs.pop_front();
    Position p;
    stream_off = D.base + off;
    if (!D.segs.empty()) {
      const Seg& s = D.segs.front();
      p.record = s.record;
      p.offset = s.rec_off + (off >= s.stream_off ? off - s.stream_off : 0);
      // the time of the chunk that holds the item's last byte
      std::uint64_t last = off + (len ? len - 1 : 0);
      for (const Seg& x : D.segs) {
        if (x.stream_off > last) break;
        if (x.ts != kNoTime) ts = x.ts;
      }
    }
    if (p.record != D.last_record) {
      D.last_record = p.record;
      D.index = 0;
    }
    p.index = D.index++;
    return p;
  }

  void drain_stream(Conversation& c, int d, std::int64_t ts) {
    Direction& D = c.dir[d];
    top::StreamItem it;
    while (D.dec.next(it)) {
      std::uint64_t so = 0;
      std::int64_t t = ts;
      Position pos = map_position(D, it.offset, it.length, so, t);
      item(c, d, it, pos, t, so);
    }
  }

  void item(Conversation& c, int d, top::StreamItem& it, Position pos, std::int64_t ts,
            std::uint64_t stream_off) {
    Direction& D = c.dir[d];
    if (it.kind == top::ItemKind::garbage) {
      ++A.stats_.garbage;
      ++codes[static_cast<std::size_t>(it.finding.code)];
      if (it.finding.severity > A.worst_) A.worst_ = it.finding.severity;
      if (A.filtering_ &&
          (!A.filter_.idents.empty() || !A.filter_.addrs.empty() || !A.filter_.selects_time(ts) ||
           (A.filter_.severity_set && it.finding.severity < A.filter_.min_severity)))
        return;
      GarbageEvent g;
      g.ts = ts;
      g.pos = pos;
      g.transport = c.transport;
      g.conv = &c;
      g.from = &D.from;
      g.to = &D.to;
      g.item = &it;
      A.sink_.garbage(g);
      return;
    }
    frame(c, d, it.frame, pos, ts, stream_off);
  }

  // Decoding is cheaper than any cache keyed by the frame bytes (frames of a
  // real capture are mostly distinct: angles, attitudes), so each frame is
  // decoded into one reused entry.
  const DecodedEntry& lookup(top::Frame& f, top::Dialect dialect, top::Role role) {
    DecodedEntry& e = current;
    top::DecodeOptions o;
    o.dialect = dialect;
    o.model = A.opts_.model;
    o.role = role;
    o.detail = A.opts_.detail;
    o.cache = &decode_cache;
    top::decode(f, o, e.decoded);
    if (role == top::Role::response)
      top::note_device_form(f, A.opts_.model, A.opts_.detail, e.decoded);
    e.frame = &f;
    // the worst severity and the bad checksum in one pass
    e.worst = top::Severity::info;
    e.bad_checksum = false;
    for (const top::Finding& x : f.findings) {
      e.worst = std::max(e.worst, x.severity);
      e.bad_checksum |= x.code == top::FindingCode::bad_checksum;
    }
    for (const top::Finding& x : e.decoded.findings) e.worst = std::max(e.worst, x.severity);
    return e;
  }

  static std::uint32_t pack(std::string_view id) {
    std::uint32_t k = 0;
    for (std::size_t i = 0; i < 3 && i < id.size(); ++i)
      k |= static_cast<std::uint32_t>(static_cast<unsigned char>(id[i])) << (8 * i);
    return k;
  }
  static std::string unpack(std::uint32_t k) {
    char b[3] = {static_cast<char>(k & 0xFF), static_cast<char>((k >> 8) & 0xFF),
                 static_cast<char>((k >> 16) & 0xFF)};
    return escape(std::string_view(b, 3));
  }

  void materialize(Stats& s) const {
    s.per_ident.clear();
    for (const auto& [k, v] : idents) s.per_ident[unpack(k)] += v;
    for (std::size_t i = 0; i < ident_table.size(); ++i)
      if (ident_table[i]) s.per_ident[top::ident_of(i)] += ident_table[i];
    s.per_code.clear();
    for (std::size_t i = 0; i < codes.size(); ++i)
      if (codes[i])
        s.per_code[std::string(top::to_string(static_cast<top::FindingCode>(i)))] += codes[i];
    for (std::size_t i = 0; i < acodes.size(); ++i)
      if (acodes[i]) s.per_code[std::string(to_string(static_cast<ACode>(i)))] += acodes[i];
    s.latency.clear();
    for (std::size_t i = 0; i < latency_keys.size(); ++i)
      s.latency[unpack(latency_keys[i])] = latency[i];
  }

  void frame(Conversation& c, int d, top::Frame& f, Position pos, std::int64_t ts,
             std::uint64_t stream_off) {
    Direction& D = c.dir[d];
    if (c.observed < 64) {
      c.det.observe(f);
      ++c.observed;
    }
    top::Dialect dialect = c.det.current();
    if (dialect == top::Dialect::unknown) dialect = top::dialect_from_frame(f);
    if (c.device_dir < 0) learn_device(c, d, f, dialect);
    // The device's frames are responses and pushes whatever their address
    // order (real C12s push #tpUGCrGAC, client first); the client's are
    // requests.
    top::Role role = top::Role::any;
    if (c.device_dir >= 0) role = d == c.device_dir ? top::Role::response : top::Role::request;
    const DecodedEntry& e = lookup(f, dialect, role);
    const top::Frame& fr = *e.frame;

    FrameEvent ev;
    ev.n = ++A.frame_no_;
    ev.ts = ts;
    ev.pos = pos;
    ev.stream_offset = stream_off;
    ev.transport = c.transport;
    ev.conv = &c;
    ev.from = &D.from;
    ev.to = &D.to;
    ev.entry = &e;

    expire(c, ts);
    // Requests that expire now were unanswered before this frame: the
    // silence they belong to ends with it when it comes from the device.
    if (c.silence.count && d != c.silence.dir) emit_silence(c);
    D.last_frame_ts = ts;
    D.sent_frame = true;
    ++c.st.frames;
    if (e.decoded.role == top::Role::request)
      request(c, d, ev);
    else if (e.decoded.role == top::Role::response)
      response(c, d, ev);

    if (ev.worst() > A.worst_) A.worst_ = ev.worst();
    for (const Note& n : ev.notes) ++acodes[static_cast<std::size_t>(n.code)];
    if (A.filtering_ && !A.filter_.selects(ev)) return;
    if (A.opts_.stats) {
      Stats& s = A.stats_;
      ++s.frames;
      if (e.bad_checksum) ++s.bad_checksum;
      if (e.worst == top::Severity::error) ++s.error_frames;
      count_ident(fr.ident);
      for (const top::Finding& x : fr.findings) ++codes[static_cast<std::size_t>(x.code)];
      for (const top::Finding& x : e.decoded.findings) ++codes[static_cast<std::size_t>(x.code)];
      if (ts != kNoTime) {
        if (s.first == kNoTime || ts < s.first) s.first = ts;
        if (s.last == kNoTime || ts > s.last) s.last = ts;
      }
    }
    A.sink_.frame(ev);
  }

  // --- sessions ------------------------------------------------------------

  // Learns which direction the device sends in from a frame of direction d,
  // when the ports did not say: a frame addressed to a client, or one that
  // answers a pending request of the other direction, comes from the
  // device; a stream switch (GAA, GIA, FAE write) comes from a client.
  void learn_device(Conversation& c, int d, const top::Frame& f, top::Dialect dialect) {
    // Both ends the same (a recording without ports): the addresses decide.
    if (c.dir[0].src == c.dir[0].dst) return;
    if (top::role_from_addresses(f) == top::Role::response) {
      c.device_dir = d;
      return;
    }
    if (c.pending_count(f.ident, 1 - d) > 0) {
      for (std::size_t i = 0; i < c.pending.size(); ++i) {
        const Pending& p = c.pending[i];
        if (p.dir != d && same_ident(p.ident, f.ident_view())) {
          c.device_dir = d;
          return;
        }
      }
    }
    if (f.control == 'w' && dialect != top::Dialect::unknown &&
        top::stream_enabled_by(dialect, f.ident_view()))
      c.device_dir = 1 - d;
  }

  static bool same_ident(const char a[3], std::string_view b) {
    return b.size() == 3 && a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
  }

  void unanswered(Conversation& c, const Pending& p, bool at_end) {
    // A copy of a request that was answered (senders that send each frame
    // several times) is not unanswered: the device answered one of them.
    if (p.ts != kNoTime)
      for (const Answered& a : c.answered)
        if (a.ts != kNoTime && same_ident(p.ident, std::string_view(a.ident, 3)) &&
            a.control == p.control && a.src == p.src && a.dst == p.dst && a.data == p.data &&
            std::llabs(a.ts - p.ts) <= std::max<std::int64_t>(A.opts_.repeat_window_us, 0))
          return;
    ++A.stats_.unanswered;
    const Direction& D = c.dir[p.dir];
    const Direction& other = c.dir[1 - p.dir];
    const bool silent =
        p.cause == Cause::none && p.ts != kNoTime &&
        (!other.sent_frame || other.last_frame_ts == kNoTime || other.last_frame_ts < p.ts);
    std::string msg = message([&] {
      std::string m =
          escape(std::string_view(p.ident, 3)) + " request (frame " + std::to_string(p.n) + ")" +
          (at_end ? std::string(" got no response before the end of the capture")
                  : " got no response within " + std::to_string(A.opts_.timeout_us / 1000) + " ms");
      switch (p.cause) {
        case Cause::bad_checksum:
          m += ": its checksum is bad, and devices drop such frames";
          break;
        case Cause::uart_source:
          m += ": a Topotek request with source U over the network; the device answers U "
               "requests on its UART only (the network client is P)";
          break;
        case Cause::unsupported:
          m += ": the identifier is not supported on the model";
          break;
        case Cause::invalid:
          m += ": the request is invalid (its length or a value), which devices ignore or "
               "answer with ERE";
          break;
        case Cause::none:
          break;
      }
      return m;
    });
    if (silent) {
      Silence& s = c.silence;
      if (s.count && s.dir != p.dir) emit_silence(c);
      if (s.count == 0) {
        s.first_n = p.n;
        s.first_ts = p.ts;
        s.pos = p.pos;
        s.dir = p.dir;
        s.idents.clear();
        s.single = std::move(msg);
      }
      ++s.count;
      s.last_n = p.n;
      s.last_ts = p.ts;
      const std::string id = escape(std::string_view(p.ident, 3));
      if (s.idents.find(id) == std::string::npos && s.idents.size() < 64)
        s.idents += (s.idents.empty() ? "" : ", ") + id;
      return;
    }
    note_event(p.ts, p.pos, c.transport, &c, &D.from, &D.to,
               Note{ACode::unanswered, default_severity(ACode::unanswered), std::move(msg), p.n});
  }

  // One finding for requests that went unanswered while the device said
  // nothing (the first request's message when it is alone).
  void emit_silence(Conversation& c) {
    Silence& s = c.silence;
    if (s.count == 0) return;
    const Direction& D = c.dir[s.dir];
    std::string msg = s.count == 1 ? std::move(s.single) : message([&] {
      char span[32];
      std::snprintf(span, sizeof span, "%.3f", static_cast<double>(s.last_ts - s.first_ts) / 1e6);
      return "the device was silent: " + std::to_string(s.count) + " requests (" + s.idents +
             ") from frame " + std::to_string(s.first_n) + " to frame " + std::to_string(s.last_n) +
             " over " + span + " s got no response";
    });
    note_event(
        s.first_ts, s.pos, c.transport, &c, &D.from, &D.to,
        Note{ACode::unanswered, default_severity(ACode::unanswered), std::move(msg), s.first_n});
    s = Silence{};
  }

  void expire(Conversation& c, std::int64_t ts) {
    if (ts == kNoTime) return;
    while (c.oldest != kNoTime && ts - c.oldest > A.opts_.timeout_us) {
      unanswered(c, c.pending.front(), false);
      c.pop_pending();
    }
  }

  void request(Conversation& c, int d, FrameEvent& ev) {
    const top::Frame& f = *ev.entry->frame;
    Direction& D = c.dir[d];
    ++A.stats_.requests;
    ++c.st.requests;
    if (ev.ts != kNoTime && D.last_req_ts != kNoTime &&
        ev.ts - D.last_req_ts <= A.opts_.repeat_window_us && D.last_req == f.raw)
      ev.notes.push_back(Note{ACode::repeated, default_severity(ACode::repeated), message([&] {
                                return "same request again after " +
                                       std::to_string((ev.ts - D.last_req_ts) / 1000) + " ms";
                              }),
                              ev.n});
    D.last_req = f.raw;
    D.last_req_ts = ev.ts;
    std::string_view id = f.ident_view();
    const top::Dialect dialect = ev.entry->decoded.dialect;
    // A client stream's frame (FAI after FAE) expects no answer.
    for (StreamStat& s : c.st.streams) {
      if (s.from_client && s.ident == id) {
        ++s.frames;
        if (ev.ts != kNoTime) {
          if (s.first == kNoTime) s.first = ev.ts;
          s.last = ev.ts;
        }
        return;
      }
    }
    const top::StreamSpec* switched =
        f.control == 'w' ? top::stream_enabled_by(dialect, id) : nullptr;
    if (switched) {
      unsigned v = 0;
      bool ok = !f.data().empty();
      for (char ch : f.data()) {
        const int x = top::hex_value(ch);
        if (x < 0)
          ok = false;
        else
          v = v * 16 + static_cast<unsigned>(x);
      }
      if (ok) {
        const std::string sid(switched->push);
        auto& streams = c.st.streams;
        auto s = std::find_if(streams.begin(), streams.end(),
                              [&](const StreamStat& x) { return x.ident == sid; });
        if (v == 0) {
          // disabled: keep the measured figures
        } else {
          if (s == streams.end()) {
            streams.push_back(StreamStat{});
            s = streams.end() - 1;
          } else {
            check_stream(c, *s);
            *s = StreamStat{};
          }
          s->ident = sid;
          s->asked_by = std::string(switched->request);
          s->from_client = switched->sender == top::Sender::client;
          s->asked_hz = switched->rate_in_data ? static_cast<double>(v) : 0;
        }
      }
    }
    if (c.pending.size() >= kMaxPending) {
      unanswered(c, c.pending.front(), false);
      c.pop_pending();
    }
    Pending& p = c.pending.push_back();  // a reused slot: every member is assigned
    p.ts = ev.ts;
    p.n = ev.n;
    p.pos = ev.pos;
    std::memcpy(p.ident, f.ident, 3);
    p.control = f.control;
    p.src = f.src;
    p.dst = f.dst;
    p.data.clear();  // append into the slot's buffer: cheaper than assign's replace
    p.data.append(f.data());
    p.dir = d;
    p.cause = Cause::none;
    if (ev.entry->bad_checksum) {
      p.cause = Cause::bad_checksum;
    } else if (dialect == top::Dialect::topotek && f.src == 'U' &&
               c.transport != Transport::serial) {
      p.cause = Cause::uart_source;
    } else {
      // A request laid out as a reply (a one-char VSN read) is invalid too.
      const top::FormSpec* form = ev.entry->decoded.form;
      if (form && form->role == top::Role::response) p.cause = Cause::invalid;
      for (const top::Finding& x : ev.entry->decoded.findings) {
        if (x.code == top::FindingCode::unknown_ident ||
            (x.code == top::FindingCode::unsupported_on_model &&
             x.severity == top::Severity::error)) {
          p.cause = Cause::unsupported;
          break;
        }
        if (x.code == top::FindingCode::data_length || x.code == top::FindingCode::bad_field ||
            x.code == top::FindingCode::value_out_of_range ||
            x.code == top::FindingCode::unsupported_control)
          p.cause = Cause::invalid;
      }
    }
    c.count_pending(p, true);
    c.pending_changed();
  }

  void response(Conversation& c, int d, FrameEvent& ev) {
    const top::Frame& f = *ev.entry->frame;
    ++A.stats_.responses;
    ++c.st.responses;
    std::string_view id = f.ident_view();
    bool ere = id == "ERE";
    // The newest pending request it answers, preferring one whose data it
    // echoes. TOP frames carry no sequence number. Oldest-first would pair a
    // reply to a request that was lost (never answered) instead of the
    // retry it answers: the latency would be off by up to the timeout and
    // the retry reported unanswered. Newest-first can only swap two
    // identical requests in flight, whose latencies are alike.
    const bool none = !ere && c.pending_count(f.ident, 1 - d) == 0;
    // one pass from the newest: the first request whose data it echoes, else
    // the newest of its identifier (ERE: the newest to the device it speaks for)
    constexpr std::size_t kNone = SIZE_MAX;
    std::size_t mi = kNone;
    bool echoed = false;  // the request found carries the reply's data
    if (!none) {
      std::size_t by_ident = kNone;
      for (std::size_t i = c.pending.size(); i-- > 0;) {
        const Pending& p = c.pending[i];
        if (p.dir == d) continue;
        if (ere) {
          if (p.dst == f.src) {
            by_ident = i;
            break;
          }
          continue;
        }
        if (!same_ident(p.ident, id)) continue;
        if (p.data == f.data()) {
          mi = i;
          echoed = true;
          break;
        }
        if (by_ident == kNone) by_ident = i;
      }
      if (mi == kNone) mi = by_ident;
    }
    if (mi != kNone) {
      const Pending* m = &c.pending[mi];
      ++A.stats_.paired;
      ++c.st.paired;
      ev.reply_to = m->n;
      if (ev.ts != kNoTime && m->ts != kNoTime) {
        ev.latency_us = ev.ts - m->ts;
        latency_of(pack(std::string_view(m->ident, 3))).add(ev.latency_us);
      }
      // Writes answered in a layout of their own (Topotek REC/CAP file index,
      // LON/LAT, LRF) are not echoes.
      const top::CommandSpec* cmd = ev.entry->decoded.command;
      bool exempt = cmd && top::write_reply(*cmd) != top::WriteReply::echo;
      if (!ere && !exempt && m->control == 'w' && f.control == 'w' && !echoed)
        ev.notes.push_back(
            Note{ACode::echo_differs, default_severity(ACode::echo_differs), message([&] {
                   return "reply to write (frame " + std::to_string(m->n) + ") carries \"" +
                          escape(f.data()) + "\", the write carried \"" + escape(m->data) + "\"";
                 }),
                 ev.n});
      Answered& a = c.answered[c.answered_next++ % c.answered.size()];
      std::memcpy(a.ident, m->ident, 3);
      a.control = m->control;
      a.src = m->src;
      a.dst = m->dst;
      a.data = m->data;
      a.ts = m->ts;
      c.erase_pending(mi);
      return;
    }
    for (StreamStat& s : c.st.streams) {
      if (s.ident == id) {
        ++s.frames;
        if (ev.ts != kNoTime) {
          if (s.first == kNoTime) s.first = ev.ts;
          s.last = ev.ts;
        }
        return;
      }
    }
    ++A.stats_.unsolicited;
    ev.notes.push_back(Note{
        ACode::unsolicited, default_severity(ACode::unsolicited),
        message([&] { return escape(id) + " response that no pending request asked for"; }), ev.n});
  }

  void check_stream(Conversation& c, const StreamStat& s) {
    if (s.asked_hz <= 0 || s.frames < 2) return;
    double m = s.measured_hz();
    if (m <= 0 || std::fabs(m - s.asked_hz) <= 0.25 * s.asked_hz) return;
    // printf's "%.1f" and "%.0f" through to_chars (the same text, without
    // printf's cost on every re-asked stream)
    auto fixed = [](double v, int decimals) {
      char b[64];
      auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, decimals);
      return r.ec == std::errc() ? std::string(b, r.ptr) : std::to_string(v);
    };
    std::string msg = message([&] {
      return s.ident + " stream runs at " + fixed(m, 1) + " Hz, " + s.asked_by + " asked for " +
             fixed(s.asked_hz, 0) + " Hz (" + std::to_string(s.frames) + " frames)";
    });
    note_event(s.last, Position{}, c.transport, &c, &c.dir[0].from, &c.dir[0].to,
               Note{ACode::stream_rate, default_severity(ACode::stream_rate), std::move(msg), 0});
  }

  // --- TCP -----------------------------------------------------------------

  void deliver(Conversation& c, int d, std::string_view bytes, std::uint64_t record,
               std::uint64_t offset, std::int64_t ts) {
    Direction& D = c.dir[d];
    if (bytes.empty()) return;
    // The other direction spoke before this: release its held frame so the
    // frames come out in capture order (a CR/LF it sends later is garbage).
    c.dir[1 - d].dec.flush();
    drain_stream(c, 1 - d, ts);
    D.segs.push_back(Seg{D.dec.fed(), record, offset, ts});
    if (D.segs.size() > 4096) D.segs.pop_front();
    D.dec.feed(bytes);
    if (c.transport == Transport::tcp) {
      D.next_seq += static_cast<std::uint32_t>(bytes.size());
      D.tail.append(bytes);
      if (D.tail.size() > 8192) D.tail.erase(0, D.tail.size() - 4096);
    }
    drain_stream(c, d, ts);
  }

  void overlap_check(Conversation& c, int d, std::uint32_t seq, std::string_view bytes,
                     std::uint64_t record, std::uint64_t offset, std::int64_t ts) {
    // bytes [seq, seq+len) all lie before next_seq
    Direction& D = c.dir[d];
    std::uint32_t back = D.next_seq - seq;  // distance from seq to next_seq
    std::string msg = std::to_string(bytes.size()) + " bytes at stream offset " +
                      std::to_string(D.base + D.dec.fed() - back) + " seen again";
    if (back <= D.tail.size()) {
      std::string_view old = std::string_view(D.tail).substr(D.tail.size() - back, bytes.size());
      if (old != bytes) {
        note_event(ts, Position{record, 0, offset}, c.transport, &c, &D.from, &D.to,
                   Note{ACode::tcp_overlap_differs, default_severity(ACode::tcp_overlap_differs),
                        msg + " with different content; the first copy is kept", 0});
        return;
      }
    }
    note_event(ts, Position{record, 0, offset}, c.transport, &c, &D.from, &D.to,
               Note{ACode::tcp_retransmission, default_severity(ACode::tcp_retransmission),
                    msg + " (retransmission)", 0});
  }

  // Delivers what it can of one segment at seq; returns false if it lies ahead.
  bool place(Conversation& c, int d, std::uint32_t seq, std::string_view p, std::uint64_t record,
             std::uint64_t offset, std::int64_t ts) {
    Direction& D = c.dir[d];
    auto rel = static_cast<std::int32_t>(seq - D.next_seq);
    if (rel > 0) return false;
    auto skip = static_cast<std::size_t>(-static_cast<std::int64_t>(rel));
    if (skip > 0)
      overlap_check(c, d, seq, p.substr(0, std::min(skip, p.size())), record, offset, ts);
    if (skip < p.size()) deliver(c, d, p.substr(skip), record, offset + skip, ts);
    return true;
  }

  void drain_ooo(Conversation& c, int d) {
    Direction& D = c.dir[d];
    while (!D.ooo.empty()) {
      // the held segment closest to next_seq
      auto best = D.ooo.end();
      std::int32_t best_rel = std::numeric_limits<std::int32_t>::max();
      for (auto it = D.ooo.begin(); it != D.ooo.end(); ++it) {
        auto rel = static_cast<std::int32_t>(it->first - D.next_seq);
        if (rel < best_rel) best_rel = rel, best = it;
      }
      if (best_rel > 0) return;
      Held h = std::move(best->second);
      std::uint32_t seq = best->first;
      D.held -= h.bytes.size();
      D.ooo.erase(best);
      place(c, d, seq, h.bytes, h.record, h.offset, h.ts);
    }
  }

  // Skips to the first held segment: the bytes in between were never seen.
  void gap(Conversation& c, int d, std::int64_t ts) {
    Direction& D = c.dir[d];
    if (D.ooo.empty()) return;
    auto best = D.ooo.begin();
    std::int32_t best_rel = std::numeric_limits<std::int32_t>::max();
    for (auto it = D.ooo.begin(); it != D.ooo.end(); ++it) {
      auto rel = static_cast<std::int32_t>(it->first - D.next_seq);
      if (rel < best_rel) best_rel = rel, best = it;
    }
    std::uint64_t at = D.base + D.dec.fed();
    note_event(best->second.ts, Position{best->second.record, 0, best->second.offset}, c.transport,
               &c, &D.from, &D.to,
               Note{ACode::tcp_gap, default_severity(ACode::tcp_gap),
                    std::to_string(best_rel) + " bytes missing at stream offset " +
                        std::to_string(at) + "; decoding restarts after the gap",
                    0});
    restart(c, d, ts, static_cast<std::uint64_t>(best_rel));
    D.next_seq = best->first;
    drain_ooo(c, d);
  }

  void restart(Conversation& c, int d, std::int64_t ts, std::uint64_t skipped) {
    Direction& D = c.dir[d];
    D.dec.finish();
    drain_stream(c, d, ts);
    D.base += D.dec.fed() + skipped;
    D.dec.reset();
    D.segs.clear();
    D.tail.clear();
  }

  void close(Conversation& c, std::int64_t ts) {
    for (int d = 0; d < 2; ++d) {
      Direction& D = c.dir[d];
      while (!D.ooo.empty()) gap(c, d, ts);
      D.dec.finish();
      drain_stream(c, d, ts);
    }
    while (!c.pending.empty()) {
      unanswered(c, c.pending.front(), true);
      c.pop_pending();
    }
    emit_silence(c);
    for (const StreamStat& s : c.st.streams) check_stream(c, s);
    c.st.dialect = c.det.current();
    if (A.stats_.conversations.size() < kMaxStatsConversations)
      A.stats_.conversations.push_back(c.st);
    else
      ++A.stats_.conversations_dropped;
  }
};

// ---------------------------------------------------------------------------

std::uint64_t FrameEvent::conv_id() const noexcept { return conv ? conv->id : 0; }
std::uint64_t GarbageEvent::conv_id() const noexcept { return conv ? conv->id : 0; }
std::uint64_t NoteEvent::conv_id() const noexcept { return conv ? conv->id : 0; }

Analyzer::Analyzer(AnalyzerOptions opts, Sink& sink)
    : impl_(std::make_unique<Impl>(*this)), opts_(opts), sink_(sink) {}
Analyzer::~Analyzer() = default;

const Stats& Analyzer::stats() const {
  impl_->materialize(stats_);
  return stats_;
}

void Analyzer::record(bool top_traffic) {
  ++stats_.records;
  if (!top_traffic) ++stats_.records_skipped;
}

void Analyzer::datagram(std::int64_t ts, const Endpoint& src, const Endpoint& dst,
                        std::string_view payload, std::uint64_t record, std::uint32_t offset) {
  int d = 0;
  Conversation& c = impl_->get(Transport::udp, src, dst, d);
  // The common case, a datagram of back-to-back frames (each perhaps
  // followed by CR/LF), skips the stream decoder's queue: for such bytes it
  // yields exactly these frames. A frame that fails its checksum qualifies
  // when no '#' inside it could start a frame the decoder would prefer. The
  // decoder takes over at the first byte that is anything else; its state
  // there would be empty, so it yields for the rest what it yields for the
  // whole.
  std::size_t p = 0;
  std::uint32_t index = 0;
  top::ParseResult& r = impl_->scratch;
  while (p < payload.size() && payload[p] == '#') {
    top::parse_frame(payload.substr(p), true, top::ParseOptions{}, r);
    if (r.status != top::ParseStatus::frame) break;
    if (!r.frame.checksum_ok && std::memchr(payload.data() + p + 1, '#', r.consumed - 1)) break;
    std::size_t q = p + r.consumed;
    while (q < payload.size() && (payload[q] == '\r' || payload[q] == '\n')) ++q;
    if (q != p + r.consumed) top::note_terminator(r.frame, q - p - r.consumed);
    impl_->frame(c, d, r.frame, Position{record, index++, offset + p}, ts, p);
    p = q;
  }
  if (p == payload.size()) return;
  Direction& D = c.dir[d];
  D.dec.reset();
  D.dec.feed(payload.substr(p));
  D.dec.finish();
  top::StreamItem it;
  while (D.dec.next(it)) {
    Position pos{record, index++, offset + p + it.offset};
    impl_->item(c, d, it, pos, ts, p + it.offset);
  }
}

void Analyzer::segment(std::int64_t ts, const Endpoint& src, const Endpoint& dst, std::uint32_t seq,
                       bool syn, std::string_view payload, std::uint64_t record,
                       std::uint32_t offset) {
  int d = 0;
  Conversation& c = impl_->get(Transport::tcp, src, dst, d);
  Direction& D = c.dir[d];
  if (syn) {
    if (!D.tcp_init || D.dec.fed() == 0) {
      D.tcp_init = true;
      D.next_seq = seq + 1;
    }
    seq += 1;
  }
  if (payload.empty()) return;
  if (!D.tcp_init) {
    D.tcp_init = true;
    D.next_seq = seq;
  }
  if (impl_->place(c, d, seq, payload, record, offset, ts)) {
    impl_->drain_ooo(c, d);
    return;
  }
  auto rel = static_cast<std::int32_t>(seq - D.next_seq);
  impl_->note_event(ts, Position{record, 0, offset}, c.transport, &c, &D.from, &D.to,
                    Note{ACode::tcp_out_of_order, default_severity(ACode::tcp_out_of_order),
                         std::to_string(payload.size()) + " bytes arrived " + std::to_string(rel) +
                             " bytes ahead of the stream; held",
                         0});
  auto [it, fresh] = D.ooo.try_emplace(seq, Held{std::string(payload), record, offset, ts});
  if (!fresh) {
    bool same = std::string_view(it->second.bytes).substr(0, payload.size()) ==
                payload.substr(0, it->second.bytes.size());
    ACode code = same ? ACode::tcp_retransmission : ACode::tcp_overlap_differs;
    impl_->note_event(
        ts, Position{record, 0, offset}, c.transport, &c, &D.from, &D.to,
        Note{code, default_severity(code),
             std::to_string(payload.size()) + " held bytes seen again" +
                 (same ? " (retransmission)" : " with different content; the longer copy is kept"),
             0});
    if (it->second.bytes.size() < payload.size()) {
      D.held -= it->second.bytes.size();
      it->second = Held{std::string(payload), record, offset, ts};
      D.held += payload.size();
    }
  } else {
    D.held += payload.size();
  }
  if (D.held > opts_.max_tcp_held || D.ooo.size() > kMaxTcpSegments) {
    impl_->note_event(ts, Position{record, 0, offset}, c.transport, &c, &D.from, &D.to,
                      Note{ACode::reassembly_limit, default_severity(ACode::reassembly_limit),
                           std::to_string(D.held) + " bytes in " + std::to_string(D.ooo.size()) +
                               " segments held past the limit of " +
                               std::to_string(opts_.max_tcp_held) + " bytes",
                           0});
    impl_->gap(c, d, ts);
  }
}

void Analyzer::chunk(std::int64_t ts, Transport t, const Endpoint& src, const Endpoint& dst,
                     std::string_view bytes, std::uint64_t record, std::uint64_t offset) {
  int d = 0;
  Conversation& c = impl_->get(t, src, dst, d);
  impl_->deliver(c, d, bytes, record, offset, ts);
}

void Analyzer::flush_streams() {
  for (auto& [k, c] : impl_->convs)
    for (int d = 0; d < 2; ++d) {
      c->dir[d].dec.flush();
      impl_->drain_stream(*c, d, kNoTime);
    }
}

void Analyzer::source_note(std::int64_t ts, ACode code, std::string message, std::uint64_t record,
                           std::uint64_t offset) {
  impl_->note_event(ts, Position{record, 0, offset}, Transport::udp, nullptr, nullptr, nullptr,
                    Note{code, default_severity(code), std::move(message), 0});
}

void Analyzer::finish() {
  std::vector<Conversation*> order;
  for (auto& [k, c] : impl_->convs) order.push_back(c.get());
  std::sort(order.begin(), order.end(),
            [](const Conversation* a, const Conversation* b) { return a->id < b->id; });
  for (Conversation* c : order) impl_->close(*c, kNoTime);
  impl_->cache.fill(Impl::CacheSlot{});
  impl_->convs.clear();
  std::sort(stats_.conversations.begin(), stats_.conversations.end(),
            [](const ConvStats& a, const ConvStats& b) { return a.id < b.id; });
}

}  // namespace topdump
