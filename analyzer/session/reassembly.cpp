// Byte streams: TCP segments reassembled per direction (retransmissions,
// overlaps, out of order, gaps), serial chunks fed in order, and every item
// a stream decoder yields mapped back to its record, offset and time.
#include <algorithm>
#include <limits>

#include "session.hpp"

namespace topdump {

Position Analyzer::Impl::map_position(Direction& D, std::uint64_t off, std::uint64_t len,
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
    for (std::size_t i = 0; i < D.segs.size(); ++i) {
      const Seg& x = D.segs[i];
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

void Analyzer::Impl::drain_stream(Conversation& c, int d, std::int64_t ts) {
  Direction& D = c.dir[d];
  top::StreamItem& it = drained;
  while (D.dec.next(it)) {
    std::uint64_t so = 0;
    std::int64_t t = ts;
    Position pos = map_position(D, it.offset, it.length, so, t);
    item(c, d, it, pos, t, so);
  }
}

void Analyzer::Impl::deliver(Conversation& c, int d, std::string_view bytes, std::uint64_t record,
                             std::uint64_t offset, std::int64_t ts) {
  Direction& D = c.dir[d];
  if (bytes.empty()) return;
  // The other direction spoke before this: release its held frame so the
  // frames come out in capture order (a CR/LF it sends later is garbage).
  c.dir[1 - d].dec.flush();
  drain_stream(c, 1 - d, ts);
  if (D.segs.size() == 4096) D.segs.pop_front();
  D.segs.push_back() = Seg{D.dec.fed(), record, offset, ts};
  D.dec.feed(bytes);
  if (c.transport == Transport::tcp) {
    D.next_seq += static_cast<std::uint32_t>(bytes.size());
    D.tail.append(bytes);
    if (D.tail.size() > 8192) D.tail.erase(0, D.tail.size() - 4096);
  }
  drain_stream(c, d, ts);
}

void Analyzer::Impl::overlap_check(Conversation& c, int d, std::uint32_t seq,
                                   std::string_view bytes, std::uint64_t record,
                                   std::uint64_t offset, std::int64_t ts) {
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
bool Analyzer::Impl::place(Conversation& c, int d, std::uint32_t seq, std::string_view p,
                           std::uint64_t record, std::uint64_t offset, std::int64_t ts) {
  Direction& D = c.dir[d];
  auto rel = static_cast<std::int32_t>(seq - D.next_seq);
  if (rel > 0) return false;
  auto skip = static_cast<std::size_t>(-static_cast<std::int64_t>(rel));
  if (skip > 0) overlap_check(c, d, seq, p.substr(0, std::min(skip, p.size())), record, offset, ts);
  if (skip < p.size()) deliver(c, d, p.substr(skip), record, offset + skip, ts);
  return true;
}

void Analyzer::Impl::drain_ooo(Conversation& c, int d) {
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
void Analyzer::Impl::gap(Conversation& c, int d, std::int64_t ts) {
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

void Analyzer::Impl::restart(Conversation& c, int d, std::int64_t ts, std::uint64_t skipped) {
  Direction& D = c.dir[d];
  D.dec.finish();
  drain_stream(c, d, ts);
  D.base += D.dec.fed() + skipped;
  D.dec.reset();
  D.segs.clear();
  D.tail.clear();
}
void Analyzer::segment(std::int64_t ts, const Endpoint& src, const Endpoint& dst, std::uint32_t seq,
                       bool syn, std::string_view payload, std::uint64_t record,
                       std::uint32_t offset) {
  if (filtering_ && !take(ts)) return;
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
  if (filtering_ && !take(ts)) return;
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

}  // namespace topdump
