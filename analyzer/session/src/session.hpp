// The analyzer's internals (not a public header): the state of one
// conversation and its two directions, and Analyzer::Impl. A frame goes
// through the stages in order (Impl::frame, analyzer.cpp):
//
//   datagram / byte stream --> decode --> pair --> watch --> selected --> count --> sink
//   (byte_streams.cpp,        (role,     (Pairing, (the     (the         (Counters,
//    tcp_reassembly.hpp)       catalog)   host      diagnoses' filter)    LatencyTable:
//                                         links)    detectors)            counters.hpp)
//
// Their parts live in files of one idea:
//   analyzer.cpp       the stages of a frame, items to events, the public API
//   conversations.cpp  the conversation table: lookup, cache, eviction, close
//   requests.cpp       requests and responses through the conversation's
//                      Pairing (pairing.hpp), unanswered requests, silences
//   host_links.cpp     a device that answers the client's host: copies, notes
//   streams.cpp        device streams at their end, through their detectors
//   diagnose.cpp       a detector's verdict as a note (analyzer/diagnoses/
//                      decides every diagnosis; the session feeds and emits)
//   byte_streams.cpp   byte streams: TCP through TcpReassembly
//                      (tcp_reassembly.hpp), positions, serial chunks
//   counters.cpp       frames per identifier, findings per code, latency
//   latency.cpp        latency histograms
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

#include "session/analyzer.hpp"
#include "session/conversation.hpp"
#include "session/conversation_table.hpp"
#include "session/counters.hpp"
#include "top/detail/decode_cache.hpp"

namespace topdump {

struct Analyzer::Impl {
  Analyzer& A;
  // `o`: the analyzer's options (A.opts_ is not yet set while impl_ is made)
  Impl(Analyzer& a, const AnalyzerOptions& o);

  // --- conversations.cpp: the conversation table, and closing ------------
  ConversationTable table;
  std::uint64_t limit_notes = 0;
  // The conversation of a record and the pair of ends it went between (its
  // direction: r->dir; its endpoint texts: r->from, r->to): the table's, or
  // a new one (the least recently used closed first past the limit).
  Conversation& get(Transport t, const Endpoint& src, const Endpoint& dst, const Route*& r) {
    if (Conversation* c = table.find(t, src, dst, r)) return *c;
    if (table.size() >= A.opts_.max_conversations) evict();
    return table.add(t, src, dst, r);
  }
  void evict();
  // Ends a conversation: flushes its decoders, expires its requests,
  // checks its streams and files its statistics.
  void close(Conversation& c, std::int64_t ts);

  // --- analyzer.cpp: frames and items to events --------------------------
  DecodedEntry current;
  top::detail::DecodeCache decode_cache;  // used without detail (topdump stats)
  top::ParseResult scratch;               // the one-frame datagram path parses into this
  // What the datagram path hands the stream decoder (the bytes after its
  // frames), one datagram at a time: reset, fed, finished and drained, so
  // one decoder serves every UDP conversation.
  LazyDecoder datagram_dec;
  // How the datagram path parses: without detail (topdump stats) the
  // frames' findings carry no text, which stats never shows.
  top::ParseOptions parse;

  // The counting and latency stages (counters.hpp).
  Counters counts;
  LatencyTable latencies;

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
  // A frame through the stages: decode, pair, watch (the diagnoses),
  // selected (the filter), count, and out to the sink.
  void frame(Conversation& c, int d, top::Frame& f, Position pos, std::int64_t ts,
             std::uint64_t stream_off);
  // (inlined into frame(): docs/perf/decisions.md, "The session's stages")
  [[gnu::always_inline]] const DecodedEntry& decode(Conversation& c, int d, top::Frame& f);
  [[gnu::always_inline]] void pair(Conversation& c, int d, FrameEvent& ev);
  [[gnu::always_inline]] void watch(Conversation& c, int d, const FrameEvent& ev);
  [[gnu::always_inline]] bool selected(top::Frame& f, FrameEvent& ev);
  [[gnu::always_inline]] void count(Conversation& c, const FrameEvent& ev);
  // Folds the fast counters into the statistics.
  void materialize(Stats& s) const;

  // --- requests.cpp, streams.cpp, latency.cpp: pairing and streams --------
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
  // One of them: info, about frame n (the first that shows it) and `count`
  // frames, at ts between the ends of `at`; its text made only with detail.
  template <class Make>
  void once(Conversation& c, ACode code, std::uint64_t n, std::uint64_t count, std::int64_t ts,
            const Route& at, Make&& make) {
    Note x{code, top::Severity::info, message(make), n};
    x.count = count;
    note_event(ts, Position{}, c.transport, &c, &at.from, &at.to, std::move(x));
  }
  // A write the device takes without a word (top::write_reply nothing)
  // went without one: counted for the silent-writes note.
  void silent_write(Conversation& c, const Pending& p);
  void check_stream(Conversation& c, const StreamStat& s);
  // --- the diagnoses (analyzer/diagnoses/), reported as session notes ---
  // A detector's verdict as a note: its code, severity, figure and case
  // over `n` (the addresses and cause of what it is about).
  Note note_of(diag::Found&& f, Note n = {}) const;
  // The note at the case's first time, in the case's direction.
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
