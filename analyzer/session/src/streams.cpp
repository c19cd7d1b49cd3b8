// Device streams at their end, through their detectors (stream-stalled,
// stream-never-started, stream-rate; analyzer/diagnoses/). Only a periodic
// stream is judged (top::StreamSpec::periodic): an event push (the Topotek
// OFT while tracking, ODR while detecting, ODZ while zooming) pauses with
// its cause.
#include "session.hpp"

namespace topdump {

void Analyzer::Impl::check_stream(Conversation& c, const StreamStat& s) {
  if (!s.periodic) return;
  // A stall is the device's: its pushes stopped.
  const int device = c.device_dir >= 0 ? c.device_dir : 0;
  std::optional<diag::Found> stall;
  if (!s.from_client) {
    stall = s.stall.verdict(s.ident, device);
    if (stall) diagnose(c, *stall);
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
  diag::StreamRun run{s.ident, s.asked_by, s.asked_hz, s.frames, s.first, s.last};
  run.first_push = s.stall.first_push();
  run.dir = device;
  run.stalled = stall.has_value();
  run.stalled_us = s.stall.stalled_us();
  if (std::optional<diag::Found> f = diag::StreamRate::verdict(run)) diagnose(c, std::move(*f));
}

}  // namespace topdump
