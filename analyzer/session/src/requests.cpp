// Requests and responses: requests wait in the conversation's Pairing
// (newest first, preferring an echo of their data), go unanswered after the
// timeout with the cause the capture shows, and a silent device's stretch
// is one finding; pushes count toward the streams their switches asked for.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "session.hpp"
#include "top/detail/text.hpp"
#include "top/motion.hpp"

namespace topdump {

namespace {
// ": " and the cause, appended to an unanswered request's message.
std::string cause_text(Cause c) {
  return c == Cause::none ? std::string() : top::cat({": ", describe(c)});
}
}  // namespace

// Learns which direction the device sends in from a frame of direction d,
// when the ports did not say: a frame addressed to a client, one whose
// layout only a response has (a 12-char attitude push, even from a device
// that keeps the request's address order), or one that answers a pending
// request of the other direction, comes from the device; a frame whose
// layout only a request has, or a stream switch (GAA, GIA, FAE write),
// comes from a client.
void Analyzer::Impl::learn_device(Conversation& c, int d, const top::Frame& f,
                                  top::Dialect dialect) {
  // Both ends the same (a recording without ports): the addresses decide.
  if (c.dir[0].src == c.dir[0].dst) return;
  if (top::role_from_addresses(f) == top::Role::response) {
    c.device_dir = d;
    return;
  }
  switch (top::role_from_layout(dialect, f)) {
    case top::Role::response:
      c.device_dir = d;
      return;
    case top::Role::request:
      c.device_dir = 1 - d;
      return;
    case top::Role::any:
      break;
  }
  if (c.pairing.waiting(f.ident, 1 - d)) {
    c.device_dir = d;
    return;
  }
  if (f.control == 'w' && dialect != top::Dialect::unknown &&
      top::stream_enabled_by(dialect, f.ident_view(), top::Profile::field))
    c.device_dir = 1 - d;
}

void Analyzer::Impl::unanswered(Conversation& c, const Pending& p, bool at_end) {
  if (one_way(c)) return;  // the answers are on a line nobody recorded
  // A client stream's frame (FAI) waited only for the ERE that would refuse
  // it: a device that took it without a word did as the document says
  // (SkyDroid 3.3.6.2: FAI gets no reply), also before its enable was seen.
  // (The command as decoded when it was sent, not a catalog search:
  // docs/perf/decisions.md, "An unanswered write".)
  if (p.control == 'w' && p.command && top::write_reply(*p.command) == top::WriteReply::nothing) {
    silent_write(c, p);
    return;
  }
  // A copy of a request that was answered (senders that send each frame
  // several times) is not unanswered: the device answered one of them.
  if (c.pairing.copy_of_answered(p, A.opts_.repeat_window_us)) return;
  // Nor is one whose answer the capture's end cut off: its last frame came
  // sooner after the request than the slowest answer to its identifier in
  // the conversation (a capture that stops 50 ms after a read its camera
  // answers in 105-112 ms: PixEagle bench, 20260917T044930Z-queries).
  if (at_end && cut_off(c, p)) return;
  const Route& D = p.at ? *p.at : c.dir[p.dir];
  c.watch.dropped.unanswered(p.cause, p.n, p.ts, std::string_view(p.ident, 3), p.dir);
  Note about{ACode::unanswered, default_severity(ACode::unanswered), std::string(), p.n};
  std::memcpy(about.ident, p.ident, 3);
  about.src = p.src;
  about.dst = p.dst;
  about.cause = p.cause;
  if (A.filtering_) {
    // Reported only when the filter selects it, as a note about the request.
    NoteEvent e;
    e.ts = p.ts;
    e.conv = &c;
    e.from = &D.from;
    e.to = &D.to;
    e.note = about;
    if (!A.filter_.selects(e)) return;
  }
  ++A.stats_.unanswered;
  const Direction& other = c.dir[1 - p.dir];
  const bool silent =
      p.cause == Cause::none && p.ts != kNoTime &&
      (!other.sent_frame || other.last_frame_ts == kNoTime || other.last_frame_ts < p.ts);
  std::string msg = message([&] {
    return at_end
               ? top::cat({top::escape(std::string_view(p.ident, 3)), " request (frame ",
                           std::to_string(p.n), ") got no response before the end of the capture",
                           cause_text(p.cause)})
               : top::cat({top::escape(std::string_view(p.ident, 3)), " request (frame ",
                           std::to_string(p.n), ") got no response within ",
                           std::to_string(A.opts_.timeout_us / 1000), " ms", cause_text(p.cause)});
  });
  if (silent) {
    // Not silent after all when its frames went to another port of this
    // host: a stretch of its own, noted as such.
    Endpoint to;
    const Conversation* o = table.answered_elsewhere(c, D, p.ts, to);
    const std::uint64_t oid = o ? o->id : 0;
    Silence& s = c.silence;
    if (s.stretch.count() && (s.stretch.dir() != p.dir || s.elsewhere_conv != oid)) emit_silence(c);
    if (s.stretch.count() == 0) {
      s.elsewhere = std::move(to);
      s.elsewhere_conv = oid;
      s.about = about;
      s.pos = p.pos;
      s.single = std::move(msg);
    }
    s.stretch.add(p.n, p.ts, std::string_view(p.ident, 3), p.dir, !at_end);
    return;
  }
  about.message = std::move(msg);
  note_event(p.ts, p.pos, c.transport, &c, &D.from, &D.to, std::move(about));
}

bool Analyzer::Impl::cut_off(const Conversation& c, const Pending& p) const noexcept {
  const std::int64_t heard = last_ts(c);
  if (p.ts == kNoTime || heard == kNoTime) return false;
  const std::int64_t slowest = c.slowest.of(pack_ident(std::string_view(p.ident, 3)));
  return slowest >= 0 && heard - p.ts < slowest;
}

// One finding for requests that went unanswered while the device said
// nothing (the first request's message when it is alone).
void Analyzer::Impl::emit_silence(Conversation& c) {
  Silence& s = c.silence;
  const diag::SilentStretch& st = s.stretch;
  if (st.count() == 0) return;
  const diag::Case& r = st.requests();
  const Direction& D = c.dir[st.dir()];
  Note n = s.about;  // the first request's identifier and addresses
  if (s.elsewhere_conv) {
    n.severity = top::Severity::info;
    n.cause = Cause::other_port;
    n.count = r.frames;
    n.until = r.last_ts;
    n.message = message([&] {
      return std::to_string(r.frames) + (r.frames == 1 ? " request (" : " requests (") +
             st.idents() + ") from frame " + std::to_string(r.first_frame) + " to frame " +
             std::to_string(st.last_n()) + " got no response on this port: the device sent its " +
             "frames to " + s.elsewhere.text() + " (conversation " +
             std::to_string(s.elsewhere_conv) +
             ") meanwhile: a client that does not listen there hears nothing" +
             (c.det.current() == top::Dialect::topotek
                  ? " (Topotek V1.1.3: the device answers to UDP " +
                        std::to_string(top::client_port(top::Model::sip)) + ")"
                  : "");
    });
  } else if (r.frames > 1) {
    n.cause = Cause::silent;
    if (std::optional<diag::Found> f = st.verdict())
      n = note_of(std::move(*f), std::move(n));
    else
      n.message = message([&] { return st.figure(); });
  } else {
    n.message = std::move(s.single);
  }
  note_event(r.first_ts, s.pos, c.transport, &c, &D.from, &D.to, std::move(n));
  s = Silence{};
}

// What the capture shows of why a request may go unanswered.
Cause Analyzer::Impl::cause_of(const Conversation& c, const DecodedEntry& e, top::Model model) {
  const top::Frame& f = *e.frame;
  const top::Dialect dialect = e.decoded.dialect;
  Cause cause = Cause::none;
  if (e.bad_checksum) {
    cause = Cause::bad_checksum;
  } else if (std::any_of(f.findings.begin(), f.findings.end(), [](const top::Finding& x) {
               return x.code == top::FindingCode::checksum_case;
             })) {
    cause = Cause::checksum_case;
  } else if (!top::answers_source(
                 dialect, top::Profile::field,
                 c.transport == Transport::serial ? top::Link::uart : top::Link::network, f.src)) {
    cause = Cause::uart_source;
  } else {
    // What the device does with it (top/device.hpp); a request laid out as
    // a reply (a one-char VSN read) is invalid too.
    const top::FormSpec* form = e.decoded.form;
    switch (top::rejection(e.decoded, model)) {
      case top::Rejection::unsupported:
        cause = Cause::unsupported;
        break;
      case top::Rejection::invalid:
        cause = Cause::invalid;
        break;
      case top::Rejection::none:
        if (form && form->role == top::Role::response) cause = Cause::invalid;
        break;
    }
  }
  return cause;
}

namespace {
// A rate command sent again unchanged is a refresh, not a repeat: the
// speed-refresh trait (docs/FIELD.md) stops the motors without one, and
// drivers re-send every 20-100 ms (ArduPilot's Topotek YPR at 10 Hz, its
// SkyDroid GSY/GSP at 50 Hz).
bool is_rate_refresh(const DecodedEntry& e) noexcept {
  const top::MotionSpec* m = e.decoded.command ? top::motion_of(*e.decoded.command) : nullptr;
  return m && m->kind == top::MotionKind::rate;
}
}  // namespace

void Analyzer::Impl::request(Conversation& c, int d, FrameEvent& ev) {
  const top::Frame& f = *ev.entry->frame;
  Direction& D = c.dir[d];
  if (ev.ts != kNoTime && D.last_req_ts != kNoTime &&
      ev.ts - D.last_req_ts <= A.opts_.repeat_window_us && D.last_req == f.raw &&
      !is_rate_refresh(*ev.entry))
    ev.notes.push_back(Note{ACode::repeated, default_severity(ACode::repeated), message([&] {
                              return "same request again after " +
                                     std::to_string((ev.ts - D.last_req_ts) / 1000) + " ms";
                            }),
                            ev.n});
  D.last_req = f.raw;
  D.last_req_ts = ev.ts;
  std::string_view id = f.ident_view();
  const top::Dialect dialect = ev.entry->decoded.dialect;
  // A client stream's frame (FAI after FAE) expects no answer, unless the
  // device rejects it: then it waits for the ERE that refuses it (a device
  // that keeps the document's 12 chars refuses the 14-char FAI that
  // AP_Mount_SkyDroid.cpp @ c5aa8452 send_attitude_to_gimbal() sends, PR
  // #34155), so that the ERE is not paired with the enable before it.
  for (StreamStat& s : c.st.streams) {
    if (s.from_client && s.ident == id) {
      ++s.frames;
      if (ev.ts != kNoTime) {
        if (s.first == kNoTime) s.first = ev.ts;
        s.last = ev.ts;
      }
      if (!top::answers_error_reply(dialect)) return;
      const Cause cause = cause_of(c, *ev.entry, A.opts_.model);
      if (cause != Cause::unsupported && cause != Cause::invalid) return;
      pend(c, d, ev, cause);
      return;
    }
  }
  if (const top::StreamSpec* switched = ev.entry->decoded.switches) {  // a write's
    if (const std::optional<unsigned> value = top::switch_value(f.data())) {
      const unsigned v = *value;
      const std::string sid(switched->push);
      auto& streams = c.st.streams;
      auto s = std::find_if(streams.begin(), streams.end(),
                            [&](const StreamStat& x) { return x.ident == sid; });
      const double hz = switched->rate_in_data ? static_cast<double>(v) : 0;
      if (top::switches_off(*switched, v)) {
        // disabled: keep the measured figures
        if (s != streams.end()) s->enabled = false;
      } else if (s != streams.end() && ((s->enabled && s->asked_hz == hz) || !s->periodic)) {
        // asked again for what runs (drivers re-send the enable once a
        // second): the stream goes on; so does an event push switched on
        // again (ODZ at each zoom), whose pauses are its causes'
        if (s->frames == 0) s->never.asked(ev.n, ev.ts, id);
        s->enabled = true;
      } else {
        if (s == streams.end()) {
          streams.push_back(StreamStat{});
          s = streams.end() - 1;
        } else {
          check_stream(c, *s);
          *s = StreamStat{};
        }
        s->ident = sid;
        s->asked_by = std::string(switched->request);
        s->from_client = switched->sender == top::Sender::client;
        s->periodic = switched->periodic;
        s->asked_hz = hz;
        s->never.asked(ev.n, ev.ts, id);
      }
    }
  }
  const Cause cause = cause_of(c, *ev.entry, A.opts_.model);
  c.watch.dropped.request(cause, ev.n, ev.ts, f.ident_view(), d);
  pend(c, d, ev, cause);
}

// The request waits in the conversation's pairing for its response.
void Analyzer::Impl::pend(Conversation& c, int d, const FrameEvent& ev, Cause cause) {
  const top::Frame& f = *ev.entry->frame;
  if (c.pairing.size() >= kMaxPending) {
    unanswered(c, c.pairing.oldest(), false);
    c.pairing.pop_oldest();
  }
  c.pairing.add([&](Pending& p) {  // a reused slot: every member is assigned
    p.ts = ev.ts;
    p.n = ev.n;
    p.pos = ev.pos;
    std::memcpy(p.ident, f.ident, 3);
    p.control = f.control;
    p.src = f.src;
    p.dst = f.dst;
    p.data.clear();  // append into the slot's buffer: cheaper than assign's replace
    p.data.append(f.data());
    p.dir = d;
    p.cause = cause;
    p.command = ev.entry->decoded.command;
    p.at = c.dir[d].now;
  });
}

void Analyzer::Impl::response(Conversation& c, int d, FrameEvent& ev) {
  const top::Frame& f = *ev.entry->frame;
  std::string_view id = f.ident_view();
  bool ere = top::is_error_reply(id);
  std::optional<Pairing::Match> mt = answered(c, d, f, ev.entry->decoded.dialect);
  if (mt) {
    const Pending* m = &c.pairing[mt->index];
    ev.reply_to = m->n;
    if (ev.ts != kNoTime && m->ts != kNoTime) {
      ev.latency_us = ev.ts - m->ts;
      reply_timed = true;
      reply_key = pack_ident(std::string_view(m->ident, 3));
      c.slowest.add(reply_key, ev.latency_us);
    }
    // Writes answered in a layout of their own (Topotek REC/CAP file index,
    // LON/LAT, LRF) are not echoes.
    const top::CommandSpec* cmd = ev.entry->decoded.command;
    bool exempt = cmd && top::write_reply(*cmd) != top::WriteReply::echo;
    if (!ere && !exempt && m->control == 'w' && f.control == 'w' && !mt->echoed)
      ev.notes.push_back(Note{
          ACode::echo_differs, default_severity(ACode::echo_differs), message([&] {
            return "reply to write (frame " + std::to_string(m->n) + ") carries \"" +
                   top::escape(f.data()) + "\", the write carried \"" + top::escape(m->data) + "\"";
          }),
          ev.n});
    // a stream's switch accepted (stream-never-started); an ERE refuses it
    if (m->control == 'w' && !ere)
      for (StreamStat& s : c.st.streams)
        if (s.frames == 0 && s.asked_by == std::string_view(m->ident, 3)) s.never.answered();
    if (c.link && m->at && m->at->src.port != c.dir[d].now->dst.port)
      answered_at(c, *m, *c.dir[d].now, ev.n, ev.ts);
    c.pairing.answer(mt->index);
    return;
  }
  for (StreamStat& s : c.st.streams) {
    if (s.ident == id) {
      ++s.frames;
      s.stall.push(ev.n, ev.ts, s.asked_hz);
      if (ev.ts != kNoTime) {
        if (s.first == kNoTime) s.first = ev.ts;
        s.last = ev.ts;
      }
      return;
    }
  }
  // A device's push whose switch the capture did not see (it began
  // before the capture, or the device pushes unasked, as ArduPilot's SITL
  // simulators do): a stream of its own, asked for by nobody seen. Not a
  // frame of an identifier the device answered reads of here: that is a
  // late or second answer, and a reply to a query is never a stream
  // sample (a bench that polls GAC got "stream-stalled" for its pauses).
  const top::Dialect dialect = ev.entry->decoded.dialect;
  if (const top::StreamSpec* st = top::stream_of(dialect, id);
      st && st->sender == top::Sender::device &&
      top::role_from_layout(dialect, f) == top::Role::response &&
      c.slowest.of(pack_ident(id)) < 0) {
    StreamStat& s = c.st.streams.emplace_back();
    s.ident = std::string(id);
    s.periodic = st->periodic;
    s.frames = 1;
    s.stall.push(ev.n, ev.ts, 0);
    s.first = s.last = ev.ts;
    return;
  }
  if (one_way(c)) return;  // the requests are on a line nobody recorded
  // Before the conversation's first request a reply may answer one sent
  // before the capture began (a capture started mid-session): it shows
  // nothing about the device.
  if (c.dir[0].last_req.empty() && c.dir[1].last_req.empty()) return;
  ev.notes.push_back(Note{ACode::unsolicited, default_severity(ACode::unsolicited), message([&] {
                            return top::escape(id) + " response that no pending request asked for";
                          }),
                          ev.n});
}

}  // namespace topdump
