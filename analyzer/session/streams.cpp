// Device streams: the stream-rate check of a stream a switch asked for.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "session.hpp"

namespace topdump {

void Analyzer::Impl::check_stream(Conversation& c, const StreamStat& s) {
  if (s.asked_hz <= 0 || s.frames < 2) return;
  if (!s.off_rate()) return;
  const double m = s.measured_hz();
  // printf's "%.1f" and "%.0f" through to_chars (the same text, without
  // printf's cost on every re-asked stream)
  auto fixed = [](double v, int decimals) {
    char b[64];
    auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, decimals);
    return r.ec == std::errc() ? std::string(b, r.ptr) : std::to_string(v);
  };
  std::string msg = message([&] {
    return s.ident + " stream runs at " + fixed(m, 1) + " Hz, " + s.asked_by + " asked for " +
           fixed(s.asked_hz, 0) + " Hz (" + std::to_string(s.frames) + " frames)";
  });
  Note n{ACode::stream_rate, default_severity(ACode::stream_rate), std::move(msg), 0};
  std::memcpy(n.ident, s.ident.data(), std::min<std::size_t>(s.ident.size(), 3));
  note_event(s.last, Position{}, c.transport, &c, &c.dir[0].from, &c.dir[0].to, std::move(n));
}

}  // namespace topdump
