#include "session/analyzer.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "session.hpp"
#include "top/text.hpp"

namespace topdump {

top::Severity FrameEvent::worst() const noexcept {
  top::Severity w = entry ? entry->worst : top::Severity::info;
  for (const Note& x : notes)
    if (x.severity > w) w = x.severity;
  return w;
}

void Analyzer::Impl::note_event(std::int64_t ts, Position pos, Transport t, const Conversation* c,
                                const std::string* from, const std::string* to, Note n, bool emit) {
  NoteEvent e{.ts = ts,
              .pos = pos,
              .transport = t,
              .conv = c,
              .from = from,
              .to = to,
              .note = std::move(n)};
  // What the filter leaves out is neither counted nor in the exit status.
  if (A.filtering_ && !A.filter_.selects(e)) return;
  counts.note(e.note.code);
  if (e.note.severity > A.worst_) A.worst_ = e.note.severity;
  if (e.note.severity != top::Severity::info && diagnosis_of(e.note.code)) A.diagnosed_ = true;
  if (emit) A.sink_.note(e);
}

void Analyzer::Impl::item(Conversation& c, int d, top::StreamItem& it, Position pos,
                          std::int64_t ts, std::uint64_t stream_off) {
  Direction& D = c.dir[d];
  if (it.kind == top::ItemKind::garbage) {
    const GarbageEvent g{.ts = ts,
                         .pos = pos,
                         .transport = c.transport,
                         .conv = &c,
                         .from = &D.now->from,
                         .to = &D.now->to,
                         .item = &it};
    if (c.transport == Transport::serial)
      c.watch.baud.garbage(it.length, it.preview, pos.record, ts);
    if (A.filtering_ && !A.filter_.selects(g)) return;
    ++A.stats_.garbage;
    counts.finding(it.finding.code);
    if (it.finding.severity > A.worst_) A.worst_ = it.finding.severity;
    A.sink_.garbage(g);
    return;
  }
  frame(c, d, it.frame, pos, ts, stream_off);
}

// Decoding is cheaper than any cache keyed by the frame bytes (frames of a
// real capture are mostly distinct: angles, attitudes), so each frame is
// decoded into one reused entry.
const DecodedEntry& Analyzer::Impl::lookup(top::Frame& f, top::Dialect dialect, top::Role role) {
  DecodedEntry& e = current;
  top::DecodeOptions o;
  o.dialect = dialect;
  o.model = A.opts_.model;
  o.role = role;
  o.detail = A.opts_.detail;
  e.diagnosed = top::detail::decode(f, o, &decode_cache, e.decoded);
  e.frame = &f;
  summarise(e);
  return e;
}

// The worst severity and the bad checksum in one pass.
void Analyzer::Impl::summarise(DecodedEntry& e) {
  e.worst = top::Severity::info;
  e.bad_checksum = false;
  for (const top::Finding& x : e.frame->findings) {
    e.worst = std::max(e.worst, x.severity);
    e.bad_checksum |= x.code == top::FindingCode::bad_checksum;
  }
  for (const top::Finding& x : e.decoded.findings) e.worst = std::max(e.worst, x.severity);
}

void Analyzer::Impl::mute(top::Frame& f, FrameEvent& ev) {
  const Filter& F = A.filter_;
  DecodedEntry& e = current;
  auto muted = [&](const top::Finding& x) { return F.mutes(x.code); };
  std::erase_if(f.findings, muted);
  std::erase_if(e.decoded.findings, muted);
  std::erase_if(ev.notes, [&](const Note& n) { return F.mutes(n.code); });
  summarise(e);
}

void Analyzer::Impl::materialize(Stats& s) const {
  counts.materialize(s);
  latencies.materialize(s.latency);
}

// The frame's dialect and role as its conversation knows them, decoded.
inline const DecodedEntry& Analyzer::Impl::decode(Conversation& c, int d, top::Frame& f) {
  if (c.observed < 64) {
    c.det.observe(f);
    ++c.observed;
  }
  top::Dialect dialect = c.det.current();
  if (dialect == top::Dialect::unknown) dialect = top::dialect_from_frame(f);
  if (c.device_dir < 0) learn_device(c, d, f, dialect);
  // The device's frames are responses and pushes whatever their address
  // order (real C12s push #tpUGCrGAC, client first); the client's are
  // requests.
  top::Role role = top::Role::any;
  if (c.device_dir >= 0) role = d == c.device_dir ? top::Role::response : top::Role::request;
  return lookup(f, dialect, role);
}

// Pairing: requests wait, responses answer them, the device's copies are
// copies.
inline void Analyzer::Impl::pair(Conversation& c, int d, FrameEvent& ev) {
  const DecodedEntry& e = *ev.entry;
  Direction& D = c.dir[d];
  expire(c, ev.ts);
  // Requests that expire now were unanswered before this frame: the
  // silence they belong to ends with it when it comes from the device.
  if (c.silence.stretch.count() && d != c.silence.stretch.dir()) emit_silence(c);
  D.last_frame_ts = ev.ts;
  D.sent_frame = true;
  reply_timed = false;
  // A copy of the device's last frame to another port of the client's
  // host (a real Topotek camera's fan-out) is that frame again: shown and
  // counted, never paired or judged twice.
  // (only once the conversation took another pair of ends: a device that
  // answers from its own port to the one client port copies nothing)
  if (c.link && d == c.device_dir && !c.link->routes.empty() &&
      copy_of_last(c, d, *e.frame, ev.ts, ev.n, e.decoded.dialect)) {
    ev.copy_of = c.link->last_n;
    return;
  }
  if (e.decoded.role == top::Role::request)
    request(c, d, ev);
  else if (e.decoded.role == top::Role::response)
    response(c, d, ev);
}

// The diagnoses: the detectors see every frame but the device's copies; what
// they find is reported at the conversation's end, through the filter.
inline void Analyzer::Impl::watch(Conversation& c, int d, const FrameEvent& ev) {
  const DecodedEntry& e = *ev.entry;
  const top::Frame& fr = *e.frame;
  const top::Role role = e.decoded.role;
  if (e.diagnosed) {  // the rules' prefilter (top/detail/prefilter.hpp)
    const std::string_view id = fr.ident_view(), data = fr.data();
    if (role == top::Role::response && e.decoded.dialect != top::Dialect::unknown && fr.checksum_ok)
      c.watch.device_frame(e.decoded.dialect, id, fr.control, data, ev.n, ev.ts, d);
    c.watch.dated_frame(e.decoded.form, id, data, ev.n, ev.ts, d, role == top::Role::response);
  }
  // the motion diagnoses: commands that move the gimbal and its attitude
  if (const top::MotionSpec* m = e.decoded.motion; m && fr.checksum_ok && role != top::Role::any)
    c.watch.motion().frame(*m, e.decoded.form, role == top::Role::request, fr.control, fr.data(),
                           ev.n, ev.ts, d, A.opts_.model);
}

// Pairing saw the frame; what follows is reporting, which the filter
// governs: a frame it leaves out is neither counted nor in the exit status.
inline bool Analyzer::Impl::selected(top::Frame& f, FrameEvent& ev) {
  if (!A.filtering_) return true;
  if (!A.filter_.mute.empty() || !A.filter_.amute.empty()) mute(f, ev);
  if (A.done_ || !A.filter_.selects(ev)) return false;
  if (A.filter_.max_frames && ++A.selected_ >= A.filter_.max_frames) A.done_ = true;
  return true;
}

// The counters, the conversation's statistics and the latency.
inline void Analyzer::Impl::count(Conversation& c, const FrameEvent& ev) {
  const DecodedEntry& e = *ev.entry;
  if (ev.worst() > A.worst_) A.worst_ = ev.worst();
  bool unsolicited = false;
  for (const Note& n : ev.notes) {
    counts.note(n.code);
    unsolicited |= n.code == ACode::unsolicited;
  }
  ++c.st.frames;
  // a copy is neither a request nor a response (its role is the first's)
  A.stats_.copies += ev.copy_of != 0;
  const top::Role counted = ev.copy_of ? top::Role::any : e.decoded.role;
  if (counted == top::Role::request) {
    ++A.stats_.requests;
    ++c.st.requests;
  } else if (counted == top::Role::response) {
    ++A.stats_.responses;
    ++c.st.responses;
    if (ev.reply_to) {
      ++A.stats_.paired;
      ++c.st.paired;
    }
    if (reply_timed) latencies.of(reply_key).add(ev.latency_us);
    if (unsolicited) ++A.stats_.unsolicited;
  }
  if (A.opts_.stats) {
    const top::Frame& fr = *e.frame;
    Stats& s = A.stats_;
    ++s.frames;
    if (e.bad_checksum) ++s.bad_checksum;
    if (e.worst == top::Severity::error) ++s.error_frames;
    counts.ident(fr.ident);
    for (const top::Finding& x : fr.findings) counts.finding(x.code);
    for (const top::Finding& x : e.decoded.findings) counts.finding(x.code);
    if (ev.ts != kNoTime) {
      if (s.first == kNoTime || ev.ts < s.first) s.first = ev.ts;
      if (s.last == kNoTime || ev.ts > s.last) s.last = ev.ts;
    }
  }
}

// One frame through the session's stages, in the pipeline's order.
void Analyzer::Impl::frame(Conversation& c, int d, top::Frame& f, Position pos, std::int64_t ts,
                           std::uint64_t stream_off) {
  const DecodedEntry& e = decode(c, d, f);
  const Route& at = *c.dir[d].now;
  FrameEvent ev(++A.frame_no_, ts, pos, stream_off, c.transport, &c, &at.from, &at.to, &e);
  pair(c, d, ev);
  if (ev.copy_of == 0) watch(c, d, ev);
  if (!selected(f, ev)) return;
  count(c, ev);
  A.sink_.frame(ev);
}

std::uint64_t FrameEvent::conv_id() const noexcept { return conv ? conv->id : 0; }
std::uint64_t GarbageEvent::conv_id() const noexcept { return conv ? conv->id : 0; }
std::uint64_t NoteEvent::conv_id() const noexcept { return conv ? conv->id : 0; }

Analyzer::Analyzer(AnalyzerOptions opts, Sink& sink)
    : impl_(std::make_unique<Impl>(*this, opts)), opts_(opts), sink_(sink) {
  impl_->parse.messages = opts_.detail;
}
Analyzer::~Analyzer() = default;

const Stats& Analyzer::stats() const {
  impl_->materialize(stats_);
  return stats_;
}

void Analyzer::record(bool top_traffic) {
  ++stats_.records;
  if (!top_traffic) ++stats_.records_skipped;
}

void Analyzer::datagram(std::int64_t ts, const Endpoint& src, const Endpoint& dst,
                        std::string_view payload, std::uint64_t record, std::uint32_t offset) {
  if (filtering_ && !take(ts)) return;
  const Route* route = nullptr;
  Conversation& c = impl_->get(Transport::udp, src, dst, route);
  const int d = route->dir;
  c.dir[d].now = route;
  // The common case, a datagram of back-to-back frames (each perhaps
  // followed by CR/LF), skips the stream decoder's queue: for such bytes it
  // yields exactly these frames. A frame that fails its checksum qualifies
  // when no '#' inside it could start a frame the decoder would prefer. The
  // decoder takes over at the first byte that is anything else; its state
  // there would be empty, so it yields for the rest what it yields for the
  // whole.
  std::size_t p = 0;
  std::uint32_t index = 0;
  top::ParseResult& r = impl_->scratch;
  while (p < payload.size() && payload[p] == '#') {
    top::parse_frame(payload.substr(p), true, impl_->parse, r);
    if (r.status != top::ParseStatus::frame) break;
    if (!r.frame.checksum_ok && std::memchr(payload.data() + p + 1, '#', r.consumed - 1)) break;
    std::size_t q = p + r.consumed;
    // CR/LF as the decoder counts them: any past top::kMaxTerminator are
    // garbage, which the decoder below yields.
    const std::size_t q_max = std::min(payload.size(), q + top::kMaxTerminator);
    while (q < q_max && (payload[q] == '\r' || payload[q] == '\n')) ++q;
    if (q != p + r.consumed)
      top::note_terminator(r.frame, q - p - r.consumed, impl_->parse.messages);
    impl_->frame(c, d, r.frame, Position{record, index++, offset + p}, ts, p);
    p = q;
  }
  if (p == payload.size()) return;
  LazyDecoder& dec = impl_->datagram_dec;
  dec.reset();
  dec.feed(payload.substr(p));
  dec.finish();
  top::StreamItem it;
  while (dec.next(it)) {
    Position pos{record, index++, offset + p + it.offset};
    impl_->item(c, d, it, pos, ts, p + it.offset);
  }
}

void Analyzer::source_note(std::int64_t ts, ACode code, std::string message, std::uint64_t record,
                           std::uint64_t offset) {
  impl_->note_event(ts, Position{record, 0, offset}, Transport::udp, nullptr, nullptr, nullptr,
                    Note{code, default_severity(code), std::move(message), 0});
}

void Analyzer::note_if_no_frames(std::string what) {
  if (frame_no_ > 0 || impl_->counts.notes(ACode::baud_mismatch) > 0) return;
  source_note(kNoTime, ACode::no_frames, std::move(what), 0, 0);
}

}  // namespace topdump
