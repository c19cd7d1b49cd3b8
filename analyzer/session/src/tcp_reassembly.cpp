#include "session/tcp_reassembly.hpp"

#include <algorithm>
#include <limits>

namespace topdump {

void TcpReassembly::segment(std::uint32_t seq, bool syn, std::string_view payload,
                            std::uint64_t record, std::uint32_t offset, std::int64_t ts,
                            TcpOutput& out) {
  if (syn) {
    if (!init_ || fed_ == 0) {
      init_ = true;
      next_seq_ = seq + 1;
    }
    seq += 1;
  }
  if (payload.empty()) return;
  if (!init_) {
    init_ = true;
    next_seq_ = seq;
  }
  if (place(seq, payload, record, offset, ts, out)) {
    drain(out);
    return;
  }
  hold(seq, payload, record, offset, ts, out);
}

void TcpReassembly::finish(std::int64_t ts, TcpOutput& out) {
  while (!ooo_.empty()) gap(ts, out);
}

// Holds a segment that lies ahead of the stream (the longer copy of one
// held before), and gives up on the bytes before it past the limits.
void TcpReassembly::hold(std::uint32_t seq, std::string_view payload, std::uint64_t record,
                         std::uint32_t offset, std::int64_t ts, TcpOutput& out) {
  auto rel = static_cast<std::int32_t>(seq - next_seq_);
  out.finding(ACode::tcp_out_of_order,
              std::to_string(payload.size()) + " bytes arrived " + std::to_string(rel) +
                  " bytes ahead of the stream; held",
              record, offset, ts);
  auto [it, fresh] = ooo_.try_emplace(seq, Held{std::string(payload), record, offset, ts});
  if (!fresh) {
    bool same = std::string_view(it->second.bytes).substr(0, payload.size()) ==
                payload.substr(0, it->second.bytes.size());
    ACode code = same ? ACode::tcp_retransmission : ACode::tcp_overlap_differs;
    out.finding(
        code,
        std::to_string(payload.size()) + " held bytes seen again" +
            (same ? " (retransmission)" : " with different content; the longer copy is kept"),
        record, offset, ts);
    if (it->second.bytes.size() < payload.size()) {
      held_ -= it->second.bytes.size();
      it->second = Held{std::string(payload), record, offset, ts};
      held_ += payload.size();
    }
  } else {
    held_ += payload.size();
  }
  if (held_ > max_held_ || ooo_.size() > kMaxTcpSegments) {
    out.finding(ACode::reassembly_limit,
                std::to_string(held_) + " bytes in " + std::to_string(ooo_.size()) +
                    " segments held past the limit of " + std::to_string(max_held_) + " bytes",
                record, offset, ts);
    gap(ts, out);
  }
}

void TcpReassembly::deliver(std::string_view bytes, std::uint64_t record, std::uint64_t offset,
                            std::int64_t ts, TcpOutput& out) {
  if (bytes.empty()) return;
  next_seq_ += static_cast<std::uint32_t>(bytes.size());
  stream_off_ += bytes.size();
  fed_ += bytes.size();
  tail_.append(bytes);
  if (tail_.size() > 8192) tail_.erase(0, tail_.size() - 4096);
  out.bytes(bytes, record, offset, ts);
}

void TcpReassembly::overlap_check(std::uint32_t seq, std::string_view bytes, std::uint64_t record,
                                  std::uint64_t offset, std::int64_t ts, TcpOutput& out) {
  // bytes [seq, seq+len) all lie before next_seq
  std::uint32_t back = next_seq_ - seq;  // distance from seq to next_seq
  std::string msg = std::to_string(bytes.size()) + " bytes at stream offset " +
                    std::to_string(stream_off_ - back) + " seen again";
  if (back <= tail_.size()) {
    std::string_view old = std::string_view(tail_).substr(tail_.size() - back, bytes.size());
    if (old != bytes) {
      out.finding(ACode::tcp_overlap_differs,
                  msg + " with different content; the first copy is kept", record, offset, ts);
      return;
    }
  }
  out.finding(ACode::tcp_retransmission, msg + " (retransmission)", record, offset, ts);
}

// Delivers what it can of one segment at seq; returns false if it lies ahead.
bool TcpReassembly::place(std::uint32_t seq, std::string_view p, std::uint64_t record,
                          std::uint64_t offset, std::int64_t ts, TcpOutput& out) {
  auto rel = static_cast<std::int32_t>(seq - next_seq_);
  if (rel > 0) return false;
  auto skip = static_cast<std::size_t>(-static_cast<std::int64_t>(rel));
  if (skip > 0) overlap_check(seq, p.substr(0, std::min(skip, p.size())), record, offset, ts, out);
  if (skip < p.size()) deliver(p.substr(skip), record, offset + skip, ts, out);
  return true;
}

// The held segment closest to next_seq.
std::map<std::uint32_t, TcpReassembly::Held>::iterator TcpReassembly::closest() {
  auto best = ooo_.begin();
  std::int32_t best_rel = std::numeric_limits<std::int32_t>::max();
  for (auto it = ooo_.begin(); it != ooo_.end(); ++it) {
    auto rel = static_cast<std::int32_t>(it->first - next_seq_);
    if (rel < best_rel) best_rel = rel, best = it;
  }
  return best;
}

void TcpReassembly::drain(TcpOutput& out) {
  while (!ooo_.empty()) {
    auto best = closest();
    if (static_cast<std::int32_t>(best->first - next_seq_) > 0) return;
    Held h = std::move(best->second);
    std::uint32_t seq = best->first;
    held_ -= h.bytes.size();
    ooo_.erase(best);
    place(seq, h.bytes, h.record, h.offset, h.ts, out);
  }
}

// Skips to the first held segment: the bytes in between were never seen.
void TcpReassembly::gap(std::int64_t ts, TcpOutput& out) {
  if (ooo_.empty()) return;
  auto best = closest();
  const auto best_rel = static_cast<std::int32_t>(best->first - next_seq_);
  out.finding(ACode::tcp_gap,
              std::to_string(best_rel) + " bytes missing at stream offset " +
                  std::to_string(stream_off_) + "; decoding restarts after the gap",
              best->second.record, best->second.offset, best->second.ts);
  out.gap(static_cast<std::uint64_t>(best_rel), ts);
  stream_off_ += static_cast<std::uint64_t>(best_rel);
  fed_ = 0;
  tail_.clear();
  next_seq_ = best->first;
  drain(out);
}

}  // namespace topdump
