#include "diagnoses/baud_mismatch.hpp"

#include <algorithm>

namespace topdump::diag {

void BaudWatch::garbage(std::uint64_t length, std::string_view sample, std::uint64_t record,
                        std::int64_t ts) noexcept {
  runs_.add(record, ts, {}, 0);
  bytes_ += length;
  for (char ch : sample) {
    const auto u = static_cast<unsigned char>(ch);
    ++sampled_;
    binary_ += (u < 0x20 && u != '\r' && u != '\n' && u != '\t') || u >= 0x7F;
  }
}

void BaudWatch::bytes(std::string_view b) {
  if (!head_) head_ = std::make_unique<std::string>();
  if (head_->size() < kSample) head_->append(b.substr(0, kSample - head_->size()));
}

int mavlink_chain(std::string_view b) noexcept {
  // MAVLink v1: STX 0xFE, payload length, then 4 bytes of header, the
  // payload and a 2-byte CRC (8 + length); v2: STX 0xFD, length, flags
  // (bit 0: a 13-byte signature follows), 7 more header bytes, payload,
  // CRC (12 + length, + 13 signed).
  int best = 0;
  const std::size_t starts = std::min<std::size_t>(b.size(), 512);
  for (std::size_t i = 0; i < starts; ++i) {
    int n = 0;
    std::size_t j = i;
    while (j + 2 < b.size()) {
      const auto stx = static_cast<unsigned char>(b[j]);
      const auto len = static_cast<std::size_t>(static_cast<unsigned char>(b[j + 1]));
      if (stx == 0xFE)
        j += 8 + len;
      else if (stx == 0xFD)
        j += 12 + len + ((static_cast<unsigned char>(b[j + 2]) & 1) ? 13 : 0);
      else
        break;
      ++n;
    }
    if (j + 2 >= b.size() && n > 0) --n;  // the last one is cut off: not seen whole
    best = std::max(best, n);
    if (best >= BaudWatch::kMavlinkChain) break;
  }
  return best;
}

std::optional<Found> BaudWatch::verdict() const {
  if (bytes_ < kMinBytes || sampled_ == 0 || binary_ * 4 < sampled_) return std::nullopt;
  if (head_ && mavlink_chain(*head_) >= kMavlinkChain) return std::nullopt;
  Found f{top::Diagnosis::baud_mismatch, runs_, -1, {}};
  f.c.first_frame = 0;  // no frame: the figure names the record
  f.figure = "no TOP frame in " + std::to_string(bytes_) + " bytes of the serial line, " +
             std::to_string(binary_ * 100 / sampled_) +
             "% of those sampled outside printable ASCII (from record " +
             std::to_string(runs_.first_frame) + "): the line speed is likely wrong";
  return f;
}

}  // namespace topdump::diag
