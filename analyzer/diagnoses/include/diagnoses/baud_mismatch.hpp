// baud-mismatch: a serial conversation in which no TOP frame decoded (the
// session asks verdict() only then), only
// bytes that belong to no frame, and many of them outside printable ASCII:
// what a UART read at the wrong line speed makes of TOP's ASCII frames
// (a line at the right speed carrying another protocol is mostly text and
// is not named). A binary line whose first bytes chain MAVLink packets is
// at the right speed: an autopilot port left on MAVLink (ArduPilot's
// SERIALn_PROTOCOL), not a mis-set line speed (an outside capture's case).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class BaudWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::baud_mismatch};
  // A run of bytes that belong to no frame; `sample` is its first bytes.
  void garbage(std::uint64_t length, std::string_view sample, std::uint64_t record,
               std::int64_t ts) noexcept;
  // Bytes of the line as they come (serial conversations only): the first
  // kSample are kept for the MAVLink check.
  void bytes(std::string_view b);
  std::optional<Found> verdict() const;

  static constexpr std::uint64_t kMinBytes = 64;
  static constexpr std::size_t kSample = 4096;
  // Packets in a row that make the line MAVLink.
  static constexpr int kMavlinkChain = 4;

 private:
  Case runs_;  // first_frame: the record of the first run
  std::uint64_t bytes_ = 0, sampled_ = 0, binary_ = 0;
  std::unique_ptr<std::string> head_;  // the line's first kSample bytes
};

// The most MAVLink packets (v1 0xFE, v2 0xFD with its optional signature)
// found in a row in `b`, each starting where the one before ends.
int mavlink_chain(std::string_view b) noexcept;

}  // namespace topdump::diag
