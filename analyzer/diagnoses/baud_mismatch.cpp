#include "diagnoses/baud_mismatch.hpp"

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

std::optional<Found> BaudWatch::verdict() const {
  if (bytes_ < kMinBytes || sampled_ == 0 || binary_ * 4 < sampled_) return std::nullopt;
  Found f{top::Diagnosis::baud_mismatch, runs_, -1, {}};
  f.c.first_frame = 0;  // no frame: the figure names the record
  f.figure = "no TOP frame in " + std::to_string(bytes_) + " bytes of the serial line, " +
             std::to_string(binary_ * 100 / sampled_) +
             "% of those sampled outside printable ASCII (from record " +
             std::to_string(runs_.first_frame) + "): the line speed is likely wrong";
  return f;
}

}  // namespace topdump::diag
