// Device streams at their end: the stream-rate check of a stream a switch
// asked for, and the stream's diagnoses (stream-stalled,
// stream-never-started; analyzer/diagnoses/). Every diagnosis of the
// session becomes a note here (diagnose()).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "session.hpp"

namespace topdump {

void Analyzer::Impl::diagnose(Conversation& c, diag::Found f) {
  Note n{acode_of(f.code), top::severity(f.code), message([&] { return std::move(f.figure); }),
         f.c.first_frame};
  std::memcpy(n.ident, f.c.ident, 3);
  n.count = f.c.frames;
  n.until = f.c.last_ts;
  n.axis = static_cast<std::int8_t>(f.axis);
  const Direction& D = c.dir[f.c.dir];
  note_event(f.c.first_ts, Position{}, c.transport, &c, &D.from, &D.to, std::move(n));
}

void Analyzer::Impl::check_stream(Conversation& c, const StreamStat& s) {
  if (!s.from_client) {
    if (std::optional<diag::Found> f = s.stall.verdict(s.ident)) diagnose(c, std::move(*f));
    if (std::optional<diag::Found> f = s.never.verdict(s.ident, s.frames, s.asked_hz, last_ts(c)))
      diagnose(c, std::move(*f));
  }
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
  // the stream-rate diagnosis: its case is the stream's pushes
  constexpr top::Diagnosis kRate = top::Diagnosis::stream_rate;
  Note n{acode_of(kRate), top::severity(kRate), std::move(msg), s.stall.first_push()};
  std::memcpy(n.ident, s.ident.data(), std::min<std::size_t>(s.ident.size(), 3));
  n.count = s.frames;
  n.until = s.last;
  note_event(s.last, Position{}, c.transport, &c, &c.dir[0].from, &c.dir[0].to, std::move(n));
}

}  // namespace topdump
