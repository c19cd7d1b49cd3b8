// Device streams at their end: the stream-rate check of a stream a switch
// asked for, and the stream's diagnoses (stream-stalled,
// stream-never-started; analyzer/diagnoses/). Every diagnosis of the
// session becomes a note here (diagnose()). Only a periodic stream is
// judged (top::StreamSpec::periodic): an event push (the Topotek OFT while
// tracking, ODR while detecting, ODZ while zooming) pauses with its cause.
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
  // A stall is the device's: its pushes stopped (the case's frames are
  // pushes, whatever direction the detector was told).
  const int d =
      f.code == top::Diagnosis::stream_stalled && c.device_dir >= 0 ? c.device_dir : f.c.dir;
  const Direction& D = c.dir[d];
  note_event(f.c.first_ts, Position{}, c.transport, &c, &D.from, &D.to, std::move(n));
}

void Analyzer::Impl::check_stream(Conversation& c, const StreamStat& s) {
  if (!s.periodic) return;
  bool stalled = false;
  if (!s.from_client) {
    if (std::optional<diag::Found> f = s.stall.verdict(s.ident)) {
      diagnose(c, std::move(*f));
      stalled = true;
    }
    // Pushes of any stream the same switch turns on count (Topotek GIA 01:
    // GIA frames in the field, GIC by the document).
    std::uint64_t pushes = s.frames;
    const top::Dialect dialect = c.det.current();
    for (const StreamStat& o : c.st.streams)
      if (&o != &s && o.frames && !o.from_client)
        for (const top::StreamSpec& spec : top::streams())
          if (spec.dialect == dialect && spec.request == s.asked_by && spec.push == o.ident)
            pushes += o.frames;
    if (std::optional<diag::Found> f = s.never.verdict(s.ident, pushes, s.asked_hz, last_ts(c)))
      diagnose(c, std::move(*f));
  }
  if (s.asked_hz <= 0 || s.frames < 2) return;
  if (!s.off_rate()) return;
  if (stalled && s.last != kNoTime && s.first != kNoTime) {
    // the rate without the stalls: at the rate asked, the stall is the cause
    const auto span = static_cast<double>(s.last - s.first - s.stall.stalled_us());
    const double active = span > 0 ? static_cast<double>(s.frames - 1) * 1e6 / span : 0;
    if (std::fabs(active - s.asked_hz) <= top::stream_rate_tolerance * s.asked_hz) return;
  }
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
  // the device's stream, from its first push (the case's frame) to its last
  const Direction& D = c.dir[c.device_dir >= 0 ? c.device_dir : 0];
  note_event(s.first != kNoTime ? s.first : s.last, Position{}, c.transport, &c, &D.from, &D.to,
             std::move(n));
}

}  // namespace topdump
