#include "diagnoses/stream_rate.hpp"

#include <charconv>
#include <cmath>

#include "top/device.hpp"

namespace topdump::diag {

double measured_hz(std::uint64_t frames, std::int64_t first, std::int64_t last) noexcept {
  if (frames < 2 || first == kNoTime || last <= first) return 0;
  return static_cast<double>(frames - 1) * 1e6 / static_cast<double>(last - first);
}

bool rate_within(double hz, double asked_hz) noexcept {
  return std::fabs(hz - asked_hz) <= top::stream_rate_tolerance * asked_hz;
}

namespace {
// printf's "%.1f" and "%.0f" through to_chars (the same text, without
// printf's cost on every re-asked stream)
std::string fixed(double v, int decimals) {
  char b[64];
  auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, decimals);
  return r.ec == std::errc() ? std::string(b, r.ptr) : std::to_string(v);
}
}  // namespace

std::optional<Found> StreamRate::verdict(const StreamRun& s) {
  if (s.asked_hz <= 0 || s.frames < 2) return std::nullopt;
  const double m = measured_hz(s.frames, s.first, s.last);
  if (!off_rate(m, s.asked_hz)) return std::nullopt;
  if (s.stalled && s.last != kNoTime && s.first != kNoTime) {
    // the rate without the stalls: at the rate asked, the stall is the cause
    const auto span = static_cast<double>(s.last - s.first - s.stalled_us);
    const double active = span > 0 ? static_cast<double>(s.frames - 1) * 1e6 / span : 0;
    if (rate_within(active, s.asked_hz)) return std::nullopt;
  }
  Found f{top::Diagnosis::stream_rate, {}, -1, {}};
  // its case is the stream's pushes, from its first (the case's frame) to its last
  f.c.first_frame = s.first_push;
  f.c.frames = s.frames;
  f.c.first_ts = s.first != kNoTime ? s.first : s.last;
  f.c.last_ts = s.last;
  f.c.dir = s.dir;
  for (std::size_t i = 0; i < 3; ++i) f.c.ident[i] = i < s.ident.size() ? s.ident[i] : '\0';
  f.figure = std::string(s.ident) + " stream runs at " + fixed(m, 1) + " Hz, " +
             std::string(s.asked_by) + " asked for " + fixed(s.asked_hz, 0) + " Hz (" +
             std::to_string(s.frames) + " frames)";
  return f;
}

}  // namespace topdump::diag
