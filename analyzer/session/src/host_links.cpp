// A device that answers the client's host, not the asking port
// (top::replies_reach_host: a real Topotek camera answers from an ephemeral
// port to the asking port, to UDP 9004, twice, and to the port that asked
// before): its conversation takes every pair of ends between the two hosts
// (conversations.cpp), a copy of its last frame is that frame again, and
// what it did is noted once, at the conversation's end.
#include <algorithm>

#include "session.hpp"
#include "top/text.hpp"

namespace topdump {

namespace {
std::string ports_text(const std::vector<std::uint16_t>& v) {
  std::string s;
  for (std::uint16_t p : v) s += (s.empty() ? "" : ", ") + std::to_string(p);
  return s;
}
std::string plural(std::uint64_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}
}  // namespace

bool Analyzer::Impl::copy_of_last(Conversation& c, int d, const top::Frame& f, std::int64_t ts,
                                  std::uint64_t n, top::Dialect dialect) {
  HostLink& l = *c.link;
  const Route& r = *c.dir[d].now;
  // most frames come later than the window after the newest: nothing to compare
  if (ts != kNoTime && l.newest_ts != kNoTime && ts - l.newest_ts < top::fan_out_copy_window_us)
    for (std::size_t k = 1; k <= l.recent.size(); ++k) {  // the newest first
      HostLink::Sent& x = l.recent[(l.recent_next + l.recent.size() - k) % l.recent.size()];
      if (x.n == 0 || x.ts == kNoTime || ts < x.ts || ts - x.ts >= top::fan_out_copy_window_us ||
          f.raw != x.raw)
        continue;
      // asked again since: an answer of its own (a request older than the
      // first delivery is one the device left unanswered, not this)
      if (const auto m = answered(c, d, f, dialect); m && c.pairing[m->index].n > x.n) break;
      ++l.copies;
      if (!x.copied) ++l.fanned;
      x.copied = true;
      l.last_n = x.n;
      HostLink::note_port(l.copy_ports, r.dst.port);
      if (l.copies == 1) {
        l.copy_n = n;
        l.copy_ts = ts;
        l.copy_at = &r;
      }
      if (l.check && x.n == l.check_n && r.dst.port == l.asker) l.check = false;  // heard
      return true;
    }
  // the last reply's copies are in once the window has passed
  if (l.check &&
      (ts == kNoTime || l.check_ts == kNoTime || ts - l.check_ts >= top::fan_out_copy_window_us))
    settle(c);
  HostLink::Sent& x = l.recent[l.recent_next++ % l.recent.size()];
  x.raw.assign(f.raw);
  x.ts = ts;
  l.newest_ts = ts;
  x.n = n;
  x.copied = false;
  ++l.device_frames;
  if (r.src.port != l.device.port && l.from_reply_port++ == 0) {
    l.reply_port_n = n;
    l.reply_port_ts = ts;
    l.reply_port_at = &r;
  }
  return false;
}

void Analyzer::Impl::answered_at(Conversation& c, const Pending& p, const Route& reply,
                                 std::uint64_t n, std::int64_t ts) {
  HostLink& l = *c.link;
  if (l.check) settle(c);  // an earlier reply still waiting for its copies
  l.check = true;
  l.check_n = n;
  l.check_ts = ts;
  l.asker = p.at->src.port;
  l.asked = p;
  l.reached = reply.to;
}

void Analyzer::Impl::settle(Conversation& c) {
  HostLink& l = *c.link;
  if (!l.check) return;
  l.check = false;
  const Pending& p = l.asked;
  Silence& s = l.elsewhere;
  if (s.stretch.count() == 0) {
    s.pos = p.pos;
    s.about = Note{ACode::unanswered, top::Severity::info, std::string(), p.n};
    std::copy(p.ident, p.ident + 3, s.about.ident);
    s.about.src = p.src;
    s.about.dst = p.dst;
    s.elsewhere_conv = 0;
    l.elsewhere_asker = p.at ? p.at->from : std::string();
    l.elsewhere_at = p.at;
    s.single = l.reached;  // where the replies went
  }
  s.stretch.add(p.n, p.ts, std::string_view(p.ident, 3), p.dir, false);
}

void Analyzer::Impl::silent_write(Conversation& c, const Pending& p) {
  // a client stream's frame (FAI) is no write the device takes
  const top::StreamSpec* s = top::stream_of(p.command->dialect, p.command->ident);
  if (s && s->sender == top::Sender::client) return;
  if (c.silent_writes++ == 0) {
    c.silent_n = p.n;
    c.silent_ts = p.ts;
    c.silent_at = p.at;
  }
  const std::string id = top::escape(std::string_view(p.ident, 3));
  if (c.silent_idents.find(id) == std::string::npos && c.silent_idents.size() < 64)
    c.silent_idents += (c.silent_idents.empty() ? "" : ", ") + id;
}

void Analyzer::Impl::link_notes(Conversation& c) {
  const int dd = c.device_dir >= 0 ? c.device_dir : 0;
  const Direction& dev = c.dir[dd];
  const Direction& cli = c.dir[1 - dd];
  // A device that sent nothing at all took nothing either, as far as the
  // capture shows.
  if (c.silent_writes && dev.sent_frame) {
    once(c, ACode::silent_writes, c.silent_n, c.silent_writes, c.silent_ts,
         c.silent_at ? *c.silent_at : cli, [&] {
           return plural(c.silent_writes, "write", "writes") + " (" + c.silent_idents +
                  ") got no reply, as the document has it (Topotek 2: w is set/control, "
                  "with no reply form for these) and a real Topotek camera does "
                  "(docs/FIELD.md silent-writes): what they changed is the evidence they "
                  "were taken";
         });
  }
  if (!c.link) return;
  HostLink& l = *c.link;
  settle(c);
  const std::string host = [&] {
    Endpoint h = l.client_host;
    std::string t = h.text();
    return t.substr(0, t.rfind(':'));
  }();
  if (l.from_reply_port)
    once(c, ACode::reply_port, l.reply_port_n, l.from_reply_port, l.reply_port_ts,
         l.reply_port_at ? *l.reply_port_at : dev, [&] {
           return "the device " + l.device.text() + " sent " + std::to_string(l.from_reply_port) +
                  " of its " + plural(l.device_frames, "frame", "frames") + " from port " +
                  ports_text(l.reply_ports) +
                  ", not from the port it serves: they are its own, paired with the "
                  "requests of " +
                  host +
                  " (docs/FIELD.md ephemeral-reply-port: a real Topotek camera answers "
                  "from an ephemeral port)";
         });
  if (l.copies)
    once(c, ACode::fan_out, l.copy_n, l.copies, l.copy_ts, l.copy_at ? *l.copy_at : dev, [&] {
      return "the device sent " + std::to_string(l.fanned) + " of its " +
             plural(l.device_frames, "frame", "frames") + " to more than one port of " + host +
             " or twice (copies to port " + ports_text(l.copy_ports) +
             "): " + plural(l.copies, "copy", "copies") +
             ", each shown as a copy of its first and counted once (docs/FIELD.md "
             "fan-out, duplicate-to-client-port)";
    });
  Silence& s = l.elsewhere;
  if (const diag::Case& r = s.stretch.requests(); r.frames) {
    Note n = s.about;
    n.cause = Cause::other_port;
    n.count = r.frames;
    n.until = r.last_ts;
    n.message = message([&] {
      return plural(r.frames, "request", "requests") + " (" + s.stretch.idents() + ") from frame " +
             std::to_string(r.first_frame) + " to frame " + std::to_string(s.stretch.last_n()) +
             " got their response on another port: the device sent it to " + s.single +
             ", never to " + l.elsewhere_asker +
             " that asked: a client that listens only there hears nothing" +
             (l.dialect == top::Dialect::topotek
                  ? " (Topotek V1.1.3: the device answers to UDP " +
                        std::to_string(top::client_port(top::Model::sip)) + ")"
                  : "");
    });
    const Route* at = l.elsewhere_at;
    note_event(r.first_ts, s.pos, c.transport, &c, at ? &at->from : &cli.from,
               at ? &at->to : &cli.to, std::move(n));
    s = Silence{};
  }
}

}  // namespace topdump
