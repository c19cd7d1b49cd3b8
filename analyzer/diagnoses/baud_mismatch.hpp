// baud-mismatch: a serial conversation in which no TOP frame decoded (the
// session asks verdict() only then), only
// bytes that belong to no frame, and many of them outside printable ASCII:
// what a UART read at the wrong line speed makes of TOP's ASCII frames
// (a line at the right speed carrying another protocol is mostly text and
// is not named).
#pragma once

#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class BaudWatch {
 public:
  // A run of bytes that belong to no frame; `sample` is its first bytes.
  void garbage(std::uint64_t length, std::string_view sample, std::uint64_t record,
               std::int64_t ts) noexcept;
  std::optional<Found> verdict() const;

  static constexpr std::uint64_t kMinBytes = 64;

 private:
  Case runs_;  // first_frame: the record of the first run
  std::uint64_t bytes_ = 0, sampled_ = 0, binary_ = 0;
};

}  // namespace topdump::diag
