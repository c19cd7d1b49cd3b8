// Byte streams: TCP segments through each direction's reassembly
// (session/tcp_reassembly.hpp), serial chunks fed in order, and every item
// a stream decoder yields mapped back to its record, offset and time.

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
  drain_stream(c, d, ts);
}

void Analyzer::Impl::TcpSide::bytes(std::string_view b, std::uint64_t record, std::uint64_t offset,
                                    std::int64_t ts) {
  I.deliver(c, d, b, record, offset, ts);
}

void Analyzer::Impl::TcpSide::finding(ACode code, std::string message, std::uint64_t record,
                                      std::uint64_t offset, std::int64_t ts) {
  const Direction& D = c.dir[d];
  I.note_event(ts, Position{record, 0, offset}, c.transport, &c, &D.from, &D.to,
               Note{code, default_severity(code), std::move(message), 0});
}

void Analyzer::Impl::TcpSide::gap(std::uint64_t skipped, std::int64_t ts) {
  I.restart(c, d, ts, skipped);
}

void Analyzer::Impl::restart(Conversation& c, int d, std::int64_t ts, std::uint64_t skipped) {
  Direction& D = c.dir[d];
  D.dec.finish();
  drain_stream(c, d, ts);
  D.base += D.dec.fed() + skipped;
  D.dec.reset();
  D.segs.clear();
}
void Analyzer::segment(std::int64_t ts, const Endpoint& src, const Endpoint& dst, std::uint32_t seq,
                       bool syn, std::string_view payload, std::uint64_t record,
                       std::uint32_t offset) {
  if (filtering_ && !take(ts)) return;
  const Route* r = nullptr;
  Conversation& c = impl_->get(Transport::tcp, src, dst, r);
  const int d = r->dir;
  Impl::TcpSide side(*impl_, c, d);
  c.dir[d].tcp.segment(seq, syn, payload, record, offset, ts, side);
}

void Analyzer::chunk(std::int64_t ts, Transport t, const Endpoint& src, const Endpoint& dst,
                     std::string_view bytes, std::uint64_t record, std::uint64_t offset) {
  if (filtering_ && !take(ts)) return;
  const Route* r = nullptr;
  Conversation& c = impl_->get(t, src, dst, r);
  const int d = r->dir;
  // A line with no frame yet: its first bytes, for the baud-mismatch check.
  if (t == Transport::serial && !c.dir[0].sent_frame && !c.dir[1].sent_frame)
    c.watch.baud.bytes(bytes);
  impl_->deliver(c, d, bytes, record, offset, ts);
}

void Analyzer::flush_streams() {
  impl_->table.each([&](Conversation& c) {
    for (int d = 0; d < 2; ++d) {
      c.dir[d].dec.flush();
      impl_->drain_stream(c, d, kNoTime);
    }
  });
}

}  // namespace topdump
