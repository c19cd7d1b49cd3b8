// A diagnosis's case as a detector accumulates it: the first frame that
// shows it, how many frames do, the time window, the identifier and axis,
// and the measured figure. A fixed size whatever the capture's length: a
// detector keeps counts and the first frame, never a list of frames.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "capture/sink.hpp"
#include "top/diagnoses.hpp"

namespace topdump::diag {

struct Case {
  std::uint64_t first_frame = 0;  // 0: none yet
  std::uint64_t frames = 0;       // frames that show it
  std::int64_t first_ts = kNoTime, last_ts = kNoTime;
  char ident[3] = {};
  int dir = 0;  // the direction of the first frame
  bool any() const noexcept { return frames != 0; }
  // One more frame shows it.
  void add(std::uint64_t n, std::int64_t ts, std::string_view id, int d) noexcept {
    if (frames++ == 0) {
      first_frame = n;
      first_ts = ts;
      dir = d;
      for (std::size_t i = 0; i < 3; ++i) ident[i] = i < id.size() ? id[i] : '\0';
    }
    if (ts != kNoTime) last_ts = ts;
  }
};

// A diagnosis found: its code, its case and the figure for people.
struct Found {
  top::Diagnosis code{};
  Case c;
  int axis = -1;  // 0 yaw, 1 pitch, 2 roll; -1: none
  std::string figure;
};

// "2026-06-15 10:00:00" of seconds since the epoch (UTC).
std::string date_text(std::int64_t epoch_s);
// "2026-06-15 10:00:00.250" of microseconds since the epoch (UTC).
std::string time_text(std::int64_t us);
// "%.3f" of seconds given in microseconds.
std::string seconds_text(std::int64_t us);

}  // namespace topdump::diag
