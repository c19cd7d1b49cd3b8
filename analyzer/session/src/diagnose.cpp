// The session's diagnoses stage: the detectors of analyzer/diagnoses/ are
// fed the frames they judge (watch(), analyzer.cpp: the conversation's
// Watch, as pairing does, every frame), the stretches of unanswered
// requests (requests.cpp) and the streams at their end (streams.cpp); here
// their verdicts become notes. No diagnosis is decided in the session.
#include <cstring>

#include "session.hpp"

namespace topdump {

Note Analyzer::Impl::note_of(diag::Found&& f, Note n) const {
  n.code = acode_of(f.code);
  n.severity = top::severity(f.code);
  n.message = message([&] { return std::move(f.figure); });
  n.frame = f.c.first_frame;
  std::memcpy(n.ident, f.c.ident, 3);
  n.count = f.c.frames;
  n.until = f.c.last_ts;
  n.axis = static_cast<std::int8_t>(f.axis);
  return n;
}

void Analyzer::Impl::diagnose(Conversation& c, diag::Found f) {
  const Direction& D = c.dir[f.c.dir];
  const std::int64_t ts = f.c.first_ts;
  note_event(ts, Position{}, c.transport, &c, &D.from, &D.to, note_of(std::move(f)));
}

}  // namespace topdump
