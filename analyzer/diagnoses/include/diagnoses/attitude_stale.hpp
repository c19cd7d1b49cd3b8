// attitude-stale: non-zero motion commands keep coming while the attitude
// feedback has stopped for more than top::attitude_stale_ms: a driver
// closing its loop on a frozen attitude slews the gimbal. Judged once the
// attitude has flowed (kMinReports reports); the verdict needs kMinCommands
// such commands.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class StaleWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::attitude_stale};
  static constexpr std::uint64_t kMinReports = 3, kMinCommands = 3;
  // A non-zero motion command, frame n at ts, `last_report` the time of
  // the attitude's last report (of `attitude`, reports so far).
  void command(std::uint64_t n, std::int64_t ts, std::string_view ident, int dir,
               std::int64_t last_report, std::string_view attitude) noexcept;
  std::optional<Found> verdict() const;

 private:
  Case c_;
  std::int64_t stopped_at_ = kNoTime;  // the first episode's last report
  std::int64_t longest_us_ = 0;        // the longest age of the attitude a command met
  char attitude_[3] = {};
  std::uint32_t episodes_ = 0;
  std::int64_t episode_ = kNoTime;  // the last report of the current episode
};

}  // namespace topdump::diag
