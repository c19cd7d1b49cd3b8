#include "diagnoses/clock_offset.hpp"

#include <cstdio>
#include <cstdlib>

namespace topdump::diag {

namespace {
// "25 hours", "3.5 days": an offset under two days in whole hours.
std::string off_text(std::int64_t off) {
  const std::int64_t s = std::llabs(off);
  char b[32];
  if (s < 2 * ClockWatch::kDay)
    std::snprintf(b, sizeof b, "%lld hours", static_cast<long long>(s / 3600));
  else
    std::snprintf(b, sizeof b, "%.1f days", static_cast<double>(s) / ClockWatch::kDay);
  return b;
}
}  // namespace

void ClockWatch::frame(const top::FormSpec& form, std::string_view data, std::string_view ident,
                       std::uint64_t n, std::int64_t ts, int dir, bool device) noexcept {
  if (ts == kNoTime) return;
  const std::optional<top::DateTime> t = top::date_time_of(form, data);
  if (!t) return;
  const std::int64_t cam = top::epoch_seconds(*t), cap = ts / 1'000'000;
  if (std::llabs(cam - cap) <= kDay) return;
  if (!c_.any()) {
    camera_s_ = cam;
    capture_s_ = cap;
    sent_ = *t;
    device_ = device;
    top::DateTime next = *t;
    ++next.month;  // the month a 0-based month meant
    kind_ = std::llabs(top::epoch_seconds(next) - cap) <= kDay ? 1 : t->year <= 1970 ? 2 : 0;
  }
  c_.add(n, ts, ident, dir);
}

std::optional<Found> ClockWatch::verdict() const {
  if (!c_.any()) return std::nullopt;
  Found f{top::Diagnosis::clock_offset, c_, -1, {}};
  const std::int64_t off = camera_s_ - capture_s_;
  // Who is off: a client's set is the client's month; a camera's report
  // or echo with no client's set off before it is the camera's own clock.
  const std::string why =
      kind_ == 1   ? (device_ ? "exactly one month early, from the camera: its clock or its echo "
                                "of the time set is a month behind (a 0-based month in the "
                                "firmware, or one it kept from an earlier set)"
                              : "exactly one month early: a 0-based month sent unconverted")
      : kind_ == 2 ? (device_ ? "1970: the camera's clock was never set"
                              : "1970: the client set the camera's clock to 1970 (no time "
                                "source yet)")
                   : off_text(off) + (off < 0 ? " early" : " late");
  // A date that is no day of the calendar (31 February: a 0-based month
  // turns 31 March into it) is shown as sent, then as the day it is taken for.
  std::string cam = date_text(camera_s_);
  char sent[24];
  std::snprintf(sent, sizeof sent, "%04d-%02d-%02d", sent_.year, sent_.month, sent_.day);
  if (cam.compare(0, 10, sent) != 0) cam = std::string(sent) + " (no such date: " + cam + ")";
  f.figure = std::string(c_.ident, 3) + " camera time " + cam + ", capture " +
             date_text(capture_s_) + ": " + why + " (frame " + std::to_string(c_.first_frame) +
             (c_.frames > 1 ? ", " + std::to_string(c_.frames) + " frames" : "") + ")";
  return f;
}

}  // namespace topdump::diag
