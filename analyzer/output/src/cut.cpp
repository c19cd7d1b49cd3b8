#include "output/cut.hpp"

#include <pcap/dlt.h>

#include <algorithm>

#include "pcapio/packet.hpp"

namespace topdump {

bool Cutter::open(int dlt) {
  if (!w_) w_ = std::make_unique<pcapio::CaptureWriter>(path_, dlt);
  return w_->ok();
}

void Cutter::packet(int dlt, std::int64_t ts, std::string_view bytes, std::uint32_t len,
                    std::uint64_t record) {
  if (!packets_) {
    packets_ = true;
    open(dlt);
  }
  held_.push_back(Held{record, ts, std::string(bytes), len, false});
  held_bytes_ += bytes.size();
  while (held_.size() > kHeldPackets || held_bytes_ > kHeldBytes) evict();
}

void Cutter::evict() {
  Held& h = held_.front();
  if (h.keep && w_ && w_->ok()) {
    w_->write(h.ts, h.bytes, h.len);
    ++written_;
  }
  held_bytes_ -= h.bytes.size();
  held_.pop_front();
}

void Cutter::mark(std::uint64_t record) {
  if (held_.empty() || record < held_.front().record) {
    ++lost_;
    return;
  }
  const std::uint64_t i = record - held_.front().record;
  if (i < held_.size()) held_[i].keep = true;
}

void Cutter::frame(const FrameEvent& e) {
  if (packets_) {
    mark(e.pos.record);
    const std::string& raw = e.entry->frame->raw;
    if (e.transport == Transport::tcp && !held_.empty() && e.pos.record >= held_.front().record) {
      // the frame ends in a later segment: the first packet after its first
      // one that holds its last bytes (the decoder may emit the frame some
      // packets after that)
      const std::string_view tail =
          std::string_view(raw).substr(raw.size() - std::min<std::size_t>(raw.size(), 6));
      for (std::size_t i = e.pos.record - held_.front().record + 1; i < held_.size(); ++i)
        if (held_[i].bytes.find(tail) != std::string::npos) {
          held_[i].keep = true;
          break;
        }
    }
  } else if (open(DLT_EN10MB)) {
    auto port = [&](const std::string* name) {
      auto [it, added] =
          ports_.try_emplace(name ? *name : std::string(), static_cast<std::uint16_t>(0));
      if (added) it->second = static_cast<std::uint16_t>(kFirstSerialPort + ports_.size() - 1);
      return it->second;
    };
    const pcapio::Ip4 lo{127, 0, 0, 1};
    const std::uint16_t a = port(e.from), b = port(e.to);
    w_->write(e.ts == kNoTime ? 0 : e.ts,
              pcapio::eth(pcapio::udp4(lo, lo, a, b, e.entry->frame->raw)));
    ++written_;
  }
  inner_.frame(e);
}

bool Cutter::finish(std::string& error) {
  while (!held_.empty()) evict();
  if (!w_) open(DLT_EN10MB);  // nothing read: an empty capture
  if (!w_->close()) {
    error = w_->error();
    return false;
  }
  return true;
}

}  // namespace topdump
