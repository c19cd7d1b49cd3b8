// The analyzer's internals (not a public header): the state of one
// conversation and its two directions, and Analyzer::Impl, whose parts live
// in files of one idea:
//   analyzer.cpp       frames and items to events, statistics, the public API
//   conversations.cpp  the conversation table: lookup, cache, eviction, close
//   requests.cpp       requests and responses through the conversation's
//                      Pairing (pairing.hpp), unanswered requests, silences
//   streams.cpp        device streams: counted pushes, the stream-rate check
//   byte_streams.cpp   byte streams: TCP through TcpReassembly
//                      (tcp_reassembly.hpp), positions, serial chunks
//   latency.cpp        latency histograms and the latency table
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "diagnoses/watch.hpp"
#include "session/analyzer.hpp"
#include "session/pairing.hpp"
#include "session/tcp_reassembly.hpp"
#include "top/detail/decode_cache.hpp"
#include "top/detail/ring.hpp"

namespace topdump {

// A chunk of a direction's byte stream: where its bytes came from.
struct Seg {
  std::uint64_t stream_off;
  std::uint64_t record;
  std::uint64_t rec_off;
  std::int64_t ts;
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
  Note about;          // the first request's identifier and addresses
  // One of them waited the whole timeout inside the capture: the device
  // was silent (silent-device), not just cut off by the capture's end.
  bool timed_out = false;
  // The device was not silent: it sent frames to another port of the
  // client's host (`elsewhere`, another conversation) meanwhile.
  Endpoint elsewhere;
  std::uint64_t elsewhere_conv = 0;
};

// The pair of ends a record went between, as the conversation table found
// it: a conversation's own pair, or another pair it takes (HostLink).
struct Route {
  Endpoint src, dst;
  std::string from, to;  // endpoint texts
  int dir = 0;           // the conversation's direction this pair goes in
};

// One direction of a conversation: its own pair of ends (the Route), and
// what it decodes.
struct Direction : Route {
  // The pair the frames being decoded now went between: this one, or a
  // HostLink's (set per datagram).
  const Route* now = this;
  top::StreamDecoder dec;
  // The chunks whose bytes the decoder holds, oldest first (at most 4096).
  // A Ring, not a std::deque: a deque allocates two blocks as it is made,
  // and a conversation makes two directions, TCP or not.
  top::detail::Ring<Seg> segs;
  std::uint64_t base = 0;  // stream offset of the decoder's offset 0
  std::uint64_t last_record = 0;
  std::uint32_t index = 0;
  TcpReassembly tcp;  // TCP
  // repeats
  std::string last_req;
  std::int64_t last_req_ts = kNoTime;
  std::int64_t last_frame_ts = kNoTime;  // the last frame this direction sent
  bool sent_frame = false;
};

// What a conversation of a device that answers the client's host (not its
// port) keeps: the other pairs of ends it takes, and what the device did
// with them, for the notes at its end.
struct HostLink {
  Endpoint device;       // the end on the device's served port
  Endpoint client_host;  // the client's address, port 0
  top::Dialect dialect = top::Dialect::unknown;
  std::uint16_t client_port = 0;  // the dialect's client port (Topotek 9004), 0: none
  // The other pairs (a client port, the device's reply port) and their keys,
  // to forget them when the conversation closes.
  std::vector<std::unique_ptr<Route>> routes;
  std::vector<std::uint16_t> client_ports;  // that sent to the device (at most 16)
  std::vector<std::uint16_t> reply_ports;   // the device sent from, besides its own (at most 16)
  std::vector<std::uint16_t> copy_ports;    // copies went to (at most 16)
  std::uint64_t device_frames = 0;          // frames of the device, copies aside
  std::uint64_t from_reply_port = 0;        // of them, sent from a reply port
  std::uint64_t copies = 0;                 // copies of the device's frames
  std::uint64_t fanned = 0;                 // frames of the device that had a copy
  // The first frame from a reply port, and the first copy: where the notes sit.
  std::uint64_t reply_port_n = 0, copy_n = 0;
  std::int64_t reply_port_ts = kNoTime, copy_ts = kNoTime;
  const Route* reply_port_at = nullptr;  // the ends they went between
  const Route* copy_at = nullptr;
  // The device's last frames, a copy compared with each: the deliveries of
  // two datagrams may interleave (a real Topotek camera sent a TRC, an OFT,
  // the TRC's copy, then the OFT's: PixEagle bench, 20260918T060610Z-
  // rotated-point 06:06:14.538870).
  struct Sent {
    std::string raw;
    std::int64_t ts = kNoTime;
    std::uint64_t n = 0;
    bool copied = false;
  };
  std::array<Sent, 4> recent{};
  std::size_t recent_next = 0;
  std::int64_t newest_ts = kNoTime;  // the newest of them
  std::uint64_t last_n = 0;          // the frame the copy at hand copies
  // The last reply reached another port than its request came from
  // (`asker`): whether a copy reaches that port decides.
  bool check = false;
  std::uint16_t asker = 0;
  std::uint64_t check_n = 0;  // the reply
  std::int64_t check_ts = kNoTime;
  Pending asked{};      // the request (its route, number, time, identifier)
  std::string reached;  // the endpoint the reply went to
  // The requests whose replies never reached the port that asked: one note.
  Silence elsewhere;
  std::string elsewhere_asker;
  const Route* elsewhere_at = nullptr;  // the first such request's pair of ends
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
  // A device whose frames reach any port of the client's host from any port
  // of its own (top::replies_reach_host: Topotek): every UDP datagram
  // between the two hosts belongs here (HostLink), null otherwise.
  std::unique_ptr<HostLink> link;
  Silence silence;
  top::DialectDetector det;
  std::uint32_t observed = 0;
  Pairing pairing;
  std::uint64_t last_used = 0;
  ConvStats st;
  // The conversation's diagnoses (analyzer/diagnoses/): last, a few KB of
  // state most frames touch little of, so that the fields every frame
  // uses stay on the cache lines next to each other.
  diag::Watch watch;
  // Below: what a reply or a frame of a host link touches, after the
  // state most frames use.
  // The slowest answer per identifier (at most 8 identifiers), whatever the
  // filter selects: how long after a request the capture must go on hearing
  // the device before the request is unanswered at its end.
  struct Slowest {
    // a slot per identifier by a hash of it, then the next free one: most
    // replies find theirs at once (docs/perf/decisions.md, "The slowest
    // answer per identifier")
    std::array<std::uint32_t, 8> key{};
    std::array<std::int64_t, 8> us{};
    static std::size_t home(std::uint32_t k) noexcept { return (k * 0x9E3779B1u) >> 29; }
    void add(std::uint32_t k, std::int64_t v) noexcept {
      for (std::size_t n = 0, i = home(k); n < key.size(); ++n, i = (i + 1) % key.size())
        if (key[i] == k || key[i] == 0) {
          key[i] = k;
          if (v > us[i]) us[i] = v;
          return;
        }
    }
    std::int64_t of(std::uint32_t k) const noexcept {
      for (std::size_t n = 0, i = home(k); n < key.size() && key[i]; ++n, i = (i + 1) % key.size())
        if (key[i] == k) return us[i];
      return -1;
    }
  } slowest;
  // Writes taken without a reply, as the device's rule says
  // (top::write_reply nothing), for the silent-writes note.
  std::uint64_t silent_writes = 0;
  std::string silent_idents;
  std::uint64_t silent_n = 0;  // the first of them
  std::int64_t silent_ts = kNoTime;
  const Route* silent_at = nullptr;
};

// The conversation table's key: a transport and both ends, the lesser first.
struct ConvKey {
  Transport t;
  Endpoint a, b;  // a < b
  bool operator==(const ConvKey&) const = default;
};

struct ConvKeyHash {
  std::size_t operator()(const ConvKey& k) const noexcept;
};

// The identifier as a 24-bit key, and back as display text.
inline std::uint32_t pack_ident(std::string_view id) noexcept {
  std::uint32_t k = 0;
  for (std::size_t i = 0; i < 3 && i < id.size(); ++i)
    k |= static_cast<std::uint32_t>(static_cast<unsigned char>(id[i])) << (8 * i);
  return k;
}
std::string unpack_ident(std::uint32_t k);

struct Analyzer::Impl {
  Analyzer& A;
  explicit Impl(Analyzer& a) : A(a) {}

  // --- conversations.cpp: the conversation table -------------------------
  std::unordered_map<ConvKey, std::unique_ptr<Conversation>, ConvKeyHash> convs;
  std::uint64_t next_conv = 1;
  std::uint64_t clock = 0;
  std::uint64_t limit_notes = 0;
  // Recently used (transport, src, dst) -> conversation and direction, so
  // most records skip building and hashing a ConvKey. Checked on every hit;
  // cleared when a conversation is closed.
  struct CacheSlot {
    Conversation* c = nullptr;
    const Route* r = nullptr;  // the pair, a conversation's own or a HostLink's
  };
  std::array<CacheSlot, 64> cache{};
  // The conversations of devices that answer the client's host, by the
  // device's address: asked only for a pair of ends no conversation has.
  struct HostHash {
    std::size_t operator()(const std::array<std::uint8_t, 16>& a) const noexcept;
  };
  std::unordered_map<std::array<std::uint8_t, 16>, std::vector<Conversation*>, HostHash> links;
  // The pairs HostLinks took, to find them again (the key of each pair).
  std::unordered_map<ConvKey, std::pair<Conversation*, const Route*>, ConvKeyHash> routes;
  // The conversation a new pair of UDP ends belongs to through a HostLink
  // (and the Route it takes for the pair), or nullptr.
  Conversation* link_of(const Endpoint& src, const Endpoint& dst, const Route*& r);
  void register_link(Conversation& c);
  void forget_link(Conversation& c);
  // The network conversations of each end (both ends of each): asked only
  // when a request goes unanswered, to tell a silent device from one that
  // answers to another port of the client's host (Topotek V1.1.3: to UDP
  // 9004, whatever the request's source port).
  struct EndpointHash {
    std::size_t operator()(const Endpoint& e) const noexcept;
  };
  std::unordered_map<Endpoint, std::vector<Conversation*>, EndpointHash> by_end;
  // The conversation other than `c` in which the device end of direction D
  // of `c` sent a frame at or after `after` to another port of D's source
  // host, and that port's end; nullptr when none.
  const Conversation* answered_elsewhere(const Conversation& c, const Route& D, std::int64_t after,
                                         Endpoint& to) const;

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
  // The conversation of a record and the pair of ends it went between (its
  // direction: r->dir; its endpoint texts: r->from, r->to).
  Conversation& get(Transport t, const Endpoint& src, const Endpoint& dst, const Route*& r) {
    CacheSlot& slot = cache[cache_slot(t, src, dst)];
    if (slot.c && slot.c->transport == t && slot.r->src == src && slot.r->dst == dst) {
      slot.c->last_used = ++clock;
      r = slot.r;
      return *slot.c;
    }
    Conversation& c = get_slow(t, src, dst, r);
    slot.c = &c;
    slot.r = r;
    return c;
  }
  Conversation& get_slow(Transport t, const Endpoint& src, const Endpoint& dst, const Route*& r);
  void evict();
  // Ends a conversation: flushes its decoders, expires its requests,
  // checks its streams and files its statistics.
  void close(Conversation& c, std::int64_t ts);

  // --- analyzer.cpp: frames and items to events --------------------------
  DecodedEntry current;
  top::detail::DecodeCache decode_cache;  // used without detail (topdump stats)
  top::ParseResult scratch;               // the one-frame datagram path parses into this
  // How the datagram path parses: without detail (topdump stats) the
  // frames' findings carry no text, which stats never shows.
  top::ParseOptions parse;

  std::array<std::uint64_t, top::finding_code_count> codes{};
  std::array<std::uint64_t, acode_count> acodes{};
  // Frames per identifier of three [0-9A-Z] characters (every valid one):
  // top::ident_index's slots in 23 pages of 2048 (16 KB), each allocated
  // at the first frame counted in it and zeroed by the allocator (calloc).
  // A capture uses a few identifiers, so it pays for a few pages, not
  // 373 KB of zeroes: an analyzer that counts a handful of frames (the fuzz
  // targets build one per input) stays small, and under ASan a page is a
  // heap block, not a fresh mmap. A power of two, so finding a slot's page
  // is a shift (docs/perf/decisions.md, "Frames counted per identifier").
  static constexpr std::size_t kIdentPage = std::size_t{1} << 11;
  struct FreeDeleter {
    void operator()(std::uint64_t* p) const noexcept;
  };
  std::array<std::unique_ptr<std::uint64_t[], FreeDeleter>,
             (top::ident_slots + kIdentPage - 1) / kIdentPage>
      ident_pages;
  std::unordered_map<std::uint32_t, std::uint64_t> idents;  // other identifiers
  void count_ident(const char id[3]) {
    if (const int i = top::ident_index(id); i >= 0) {
      const auto slot = static_cast<std::size_t>(i);
      auto& page = ident_pages[slot / kIdentPage];
      if (!page) allocate_ident_page(page);
      ++page[slot % kIdentPage];
    } else {
      ++idents[pack_ident(std::string_view(id, 3))];
    }
  }
  static void allocate_ident_page(std::unique_ptr<std::uint64_t[], FreeDeleter>& page);

  // A finding's or note's message, built only when events are described
  // (AnalyzerOptions::detail); topdump stats counts them without text.
  template <class Make>
  std::string message(Make&& make) const {
    return A.opts_.detail ? std::string(make()) : std::string();
  }

  void note_event(std::int64_t ts, Position pos, Transport t, const Conversation* c,
                  const std::string* from, const std::string* to, Note n, bool emit = true);
  void item(Conversation& c, int d, top::StreamItem& it, Position pos, std::int64_t ts,
            std::uint64_t stream_off);
  const DecodedEntry& lookup(top::Frame& f, top::Dialect dialect, top::Role role);
  static void summarise(DecodedEntry& e);
  // Drops the findings the filter mutes from a frame and its notes.
  void mute(top::Frame& f, FrameEvent& ev);
  void frame(Conversation& c, int d, top::Frame& f, Position pos, std::int64_t ts,
             std::uint64_t stream_off);
  // Folds the fast counters into the statistics.
  void materialize(Stats& s) const;

  // --- requests.cpp, streams.cpp, latency.cpp: pairing and streams --------
  // Latency per identifier: a capture pairs a handful of identifiers, so a
  // linear search of their keys beats hashing (a division per reply).
  std::vector<std::uint32_t> latency_keys;
  std::vector<Latency> latency;  // latency[i] is latency_keys[i]'s
  // The last index found for each of 64 hashed slots: most replies find
  // their identifier's table there without a search (docs/perf/decisions.md,
  // "Latency tables").
  std::array<std::uint32_t, 64> latency_hint{};  // 1 + index into latency, 0: none
  Latency& latency_of(std::uint32_t key);
  // The response at hand answered a request at a known time: its latency
  // counts, under the request's identifier, when the filter selects it.
  bool reply_timed = false;
  std::uint32_t reply_key = 0;

  void pend(Conversation& c, int d, const FrameEvent& ev, Cause cause);
  // Whether the conversation's last frame came sooner after request `p`
  // than the slowest answer its identifier got in it: the capture's end may
  // have cut the answer off.
  bool cut_off(const Conversation& c, const Pending& p) const noexcept;
  void learn_device(Conversation& c, int d, const top::Frame& f, top::Dialect dialect);
  // What the capture shows of why a request may go unanswered.
  static Cause cause_of(const Conversation& c, const DecodedEntry& e, top::Model model);
  void request(Conversation& c, int d, FrameEvent& ev);
  // The pending request a device frame `f` sent in direction `d` answers.
  std::optional<Pairing::Match> answered(const Conversation& c, int d, const top::Frame& f,
                                         top::Dialect dialect) const;
  void response(Conversation& c, int d, FrameEvent& ev);
  // Requests older than the timeout at time ts are unanswered.
  void expire(Conversation& c, std::int64_t ts) {
    c.pairing.expire(ts, A.opts_.timeout_us, [&](const Pending& p) { unanswered(c, p, false); });
  }
  void unanswered(Conversation& c, const Pending& p, bool at_end);
  // A serial line recorded in one direction only (a raw dump, one tap): its
  // frames are neither unsolicited nor unanswered, as far as it shows. A
  // recording that holds both directions by construction (socat's relay
  // log, two taps merged) is never one way: its silent side is the device's.
  bool one_way(const Conversation& c) const noexcept {
    auto silent = [](const Direction& D) { return D.dec.fed() == 0 && D.base == 0; };
    return c.transport == Transport::serial && !A.both_ways_ &&
           (silent(c.dir[0]) || silent(c.dir[1]));
  }
  void emit_silence(Conversation& c);
  // --- host_links.cpp: a device that answers the client's host ----------
  // Whether frame `f` of the device, sent in direction `d`, is a copy of
  // one of its last frames (fan-out): the same bytes within the copy window
  // while no request it would answer is pending (a client that asks again
  // within the window gets an answer of its own); bookkeeping of the frames
  // that are not.
  bool copy_of_last(Conversation& c, int d, const top::Frame& f, std::int64_t ts, std::uint64_t n,
                    top::Dialect dialect);
  // The reply at hand answered request `p` on another port than `p` asked
  // from: a copy to that port may yet come.
  void answered_at(Conversation& c, const Pending& p, const Route& reply, std::uint64_t n,
                   std::int64_t ts);
  // The last reply's copies are all in: did one reach its asking port?
  void settle(Conversation& c);
  // The notes of what the device did, once per conversation, at its end.
  void link_notes(Conversation& c);
  // A write the device takes without a word (top::write_reply nothing)
  // went without one: counted for the silent-writes note.
  void silent_write(Conversation& c, const Pending& p);
  void check_stream(Conversation& c, const StreamStat& s);
  // --- the diagnoses (analyzer/diagnoses/), reported as session notes ---
  void diagnose(Conversation& c, diag::Found f);
  static std::int64_t last_ts(const Conversation& c) noexcept {
    return std::max(c.dir[0].last_frame_ts, c.dir[1].last_frame_ts);
  }

  // --- byte_streams.cpp: byte streams --------------------------------------
  Position map_position(Direction& D, std::uint64_t off, std::uint64_t len,
                        std::uint64_t& stream_off, std::int64_t& ts);
  void drain_stream(Conversation& c, int d, std::int64_t ts);
  // The item drain_stream() takes each next() into. Kept: next() swaps the
  // buffers of the item it is given back into the decoder's ring, so a
  // local one took the last frame's raw bytes and findings with it, freed,
  // at the end of every drain (and the decoder allocated them again).
  top::StreamItem drained;
  void deliver(Conversation& c, int d, std::string_view bytes, std::uint64_t record,
               std::uint64_t offset, std::int64_t ts);
  void restart(Conversation& c, int d, std::int64_t ts, std::uint64_t skipped);
  // What a direction's TCP reassembly finds: bytes for its decoder,
  // findings as notes, and gaps, after which the decoder restarts.
  struct TcpSide final : TcpOutput {
    TcpSide(Impl& i, Conversation& conv, int dir) : I(i), c(conv), d(dir) {}
    void bytes(std::string_view b, std::uint64_t record, std::uint64_t offset,
               std::int64_t ts) override;
    void finding(ACode code, std::string message, std::uint64_t record, std::uint64_t offset,
                 std::int64_t ts) override;
    void gap(std::uint64_t skipped, std::int64_t ts) override;
    Impl& I;
    Conversation& c;
    int d;
  };
};

// Asked for every response (and a copy's check): always inline, as the
// matching was inside response() before the copy check asked it too
// (docs/perf/decisions.md, "answered always inline").
[[gnu::always_inline]] inline std::optional<Pairing::Match> Analyzer::Impl::answered(
    const Conversation& c, int d, const top::Frame& f, top::Dialect dialect) const {
  const std::string_view id = f.ident_view();
  const bool ere = top::is_error_reply(id);
  // The newest pending request it answers, preferring one whose data it
  // echoes (Pairing::match).
  std::optional<Pairing::Match> mt = c.pairing.match(id, f.data(), f.control, f.src, d, ere);
  // A reply of another identifier that a recorded form names as the answer
  // to a read (a real Topotek camera answers the GIC query with GIA): the
  // newest such read pending (asked only of an identifier that answers
  // another's read: docs/perf/decisions.md, "A reply to another
  // identifier's read").
  if (!mt && !ere && top::answers_other_query(dialect, id))
    for (std::size_t i = c.pairing.size(); !mt && i-- > 0;) {
      const Pending& p = c.pairing[i];
      if (p.dir != d && p.control == 'r' && !same_ident(p.ident, id) &&
          top::answers_query(dialect, std::string_view(p.ident, 3), id))
        mt = Pairing::Match{i, false};
    }
  return mt;
}

}  // namespace topdump
