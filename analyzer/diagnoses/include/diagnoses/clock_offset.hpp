// clock-offset: the date a frame sets on the camera or reports from it
// (the year/month/day fields of its form: Topotek TIM and UTC, SkyDroid
// TIM; top::date_time_of) is more than a day off the capture's clock.
// Named: exactly one month early (a 0-based month sent unconverted) and
// 1970 (the camera's clock was never set). Whole hours are a time zone.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class ClockWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::clock_offset};
  // A frame whose form may carry a date, at capture time ts; `device`:
  // the camera sent it (a report or the echo of a set), else the client.
  void frame(const top::FormSpec& form, std::string_view data, std::string_view ident,
             std::uint64_t n, std::int64_t ts, int dir, bool device) noexcept;
  std::optional<Found> verdict() const;

  static constexpr std::int64_t kDay = 86400;

 private:
  Case c_;
  std::int64_t camera_s_ = 0, capture_s_ = 0;  // of the first frame off
  top::DateTime sent_{};                       // the first frame's date as it reads
  int kind_ = 0;                               // 1 one month early, 2 1970, 0 other
  bool device_ = false;                        // the first frame off is the camera's
};

}  // namespace topdump::diag
