#include "steps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <regex>

#include "top/decode.hpp"
#include "top/device.hpp"
#include "top/motion.hpp"

namespace topconf::detail {

namespace {

// The attitude frame `f` reports on `axis` in deg, right and up positive
// (top/motion.hpp: the row's sign under its convention), or nothing.
std::optional<double> attitude_on(top::Dialect d, const top::Frame& f, int axis) {
  const top::Decoded dec = top::decode(f, {.dialect = d, .role = top::Role::response});
  if (!dec.motion || !dec.form || dec.motion->kind != top::MotionKind::attitude) return {};
  top::MotionReading r;
  const auto ax = static_cast<std::size_t>(axis);
  if (!top::read_motion(*dec.motion, *dec.form, f.data(), r, axis) || !r.has[ax]) return {};
  for (const top::MotionAxis& a : dec.motion->fields())
    if (static_cast<int>(a.axis) == axis)
      return r.value[ax] * a.sign_in(top::field_convention(*dec.motion));
  return {};
}

// Empty when the attitudes of a "moves" stream turned as it asks, else why
// not.
std::string short_of_motion(const Expectation& e, const std::vector<double>& angles) {
  const auto axis = static_cast<top::Axis>(e.move_axis);
  const char* way = e.move_sign > 0 ? (axis == top::Axis::yaw ? "right" : "up")
                                    : (axis == top::Axis::yaw ? "left" : "down");
  char buf[200];
  if (angles.size() < 2) {
    std::snprintf(buf, sizeof buf, "%s %s: fewer than two attitudes read", e.ident.c_str(),
                  std::string(top::to_string(axis)).c_str());
    return buf;
  }
  double turn = angles.back() - angles.front();
  if (axis == top::Axis::yaw) turn = top::short_way(turn);
  if (turn * e.move_sign >= e.move_min_deg) return {};
  std::snprintf(buf, sizeof buf, "%s %s turned %+.1f deg in %u ms; at least %.1f deg %s expected",
                e.ident.c_str(), std::string(top::to_string(axis)).c_str(), turn, e.duration_ms,
                e.move_min_deg, way);
  return buf;
}

}  // namespace

// What a step saw while it watched the link.
struct CaseRunner::Watch {
  std::uint64_t start = 0;   // when the request went out
  std::uint64_t window = 0;  // ms watched
  std::uint32_t stream_ms = 0;
  std::vector<std::optional<Received>> matched;        // per alternative
  std::vector<std::vector<std::uint64_t>> push_times;  // per stream alternative
  std::vector<std::vector<double>> angles;             // per "moves": each counted push's
  std::uint64_t first_answer = 0;                      // time of the first non-push frame
  bool answered = false;
  bool duplicate = false;  // the matching reply arrived again
  std::string near_miss;
};

std::uint32_t CaseRunner::timeout_for(const Case& c, const Step& s) const {
  if (o_.timeout_ms) return *o_.timeout_ms;
  if (s.timeout_ms) return s.timeout_ms;
  if (c.timeout_ms) return c.timeout_ms;
  return m_.timeout_ms;
}

StepResult CaseRunner::run_step(const Case& c, const Step& s) {
  StepResult res;
  w_.drain();
  const std::uint32_t timeout = timeout_for(c, s);
  std::string sent;
  std::optional<top::Frame> req;
  if (s.send) {
    std::string err;
    if (!resolve_send(*s.send, m_.dialect, t_.client_address(), sent, err)) {
      res.outcome = Outcome::error;
      res.reason = "cannot build the frame: " + err;
      return res;
    }
    auto p = top::parse_exact(sent);
    if (p.status == top::ParseStatus::frame) req = p.frame;
  }
  const top::Frame* rq = req ? &*req : nullptr;
  // Readback is a dialogue of its own.
  if (s.expect.size() >= 1 && s.expect[0].kind == ExpectKind::readback)
    return run_readback(c, s, sent, rq, timeout);
  const std::vector<Alternative> alts = matcher_.prepare(s.expect, t_.client_address());

  Watch seen;
  bool has_frame_alt = false;
  std::uint32_t silence_ms = 0;
  for (const auto& e : s.expect) {
    if (e.kind == ExpectKind::silence) {
      silence_ms = std::max(silence_ms, e.silence_ms);
    } else if (e.kind == ExpectKind::stream) {
      seen.stream_ms = std::max(seen.stream_ms, e.duration_ms);
    } else if (e.kind != ExpectKind::readback) {
      has_frame_alt = true;
    }
  }
  if (s.send) w_.send(sent);
  seen.start = w_.now();
  seen.window = has_frame_alt ? timeout : 0;
  seen.window = std::max<std::uint64_t>(seen.window, silence_ms);
  seen.window = std::max<std::uint64_t>(seen.window, seen.stream_ms);
  seen.matched.resize(s.expect.size());
  seen.push_times.resize(s.expect.size());
  seen.angles.resize(s.expect.size());
  watch(s, alts, rq, seen);
  return verdict(s, seen);
}

void CaseRunner::watch(const Step& s, const std::vector<Alternative>& alts, const top::Frame* rq,
                       Watch& seen) {
  const std::uint64_t deadline = seen.start + seen.window * 1000;
  std::size_t frames = 0;
  std::uint64_t settle_deadline = 0;
  Received r;
  for (;;) {
    const std::uint64_t dl = settle_deadline ? std::min(settle_deadline, deadline) : deadline;
    if (!w_.next(dl, r)) break;
    if (++frames > o_.max_frames_per_step) {
      w_.note("more than " + std::to_string(o_.max_frames_per_step) +
              " frames in one step: flooding");
      break;
    }
    const std::string_view id = r.frame.ident_view();
    // Each stream alternative counts its own push (the document's GIC, the
    // field's GIA).
    for (std::size_t i = 0; i < s.expect.size(); ++i) {
      const Expectation& e = s.expect[i];
      if (e.kind == ExpectKind::stream && id == e.ident && r.frame.ok() &&
          r.t_us <= seen.start + std::uint64_t{e.duration_ms} * 1000 &&
          (!e.data_re || std::regex_match(std::string(r.frame.data()), *e.data_re))) {
        seen.push_times[i].push_back(r.t_us);
        if (e.move_axis >= 0)
          if (const auto a = attitude_on(m_.dialect, r.frame, e.move_axis))
            seen.angles[i].push_back(*a);
      }
    }
    // A frame of a push stream is a push, unless it answers the request: a
    // read it answers (GIC -> GIA), or a write's echo (the write's control);
    // the pushes a write switches on answer nothing.
    const bool answers_rq =
        rq && (rq->control == 'w' ? id == rq->ident_view() && r.frame.control == rq->control
                                  : top::answers_query(m_.dialect, rq->ident_view(), id));
    const bool push = is_push(m_.dialect, id) && !answers_rq;
    if (!push && !seen.answered) {
      seen.answered = true;
      seen.first_answer = r.t_us;
    }
    if (settle_deadline) {
      // Watching for duplicates of the reply that matched.
      for (const auto& mm : seen.matched)
        if (mm && mm->frame.raw == r.frame.raw) seen.duplicate = true;
      continue;
    }
    for (std::size_t i = 0; i < s.expect.size(); ++i) {
      const auto k = s.expect[i].kind;
      if (seen.matched[i] || k == ExpectKind::silence || k == ExpectKind::stream) continue;
      std::string why;
      if (matcher_.matches(alts[i], rq, r, why))
        seen.matched[i] = r;
      else if (!why.empty() && seen.near_miss.empty())
        seen.near_miss = why;
    }
    // Stop early when the first alternative that can still decide did.
    bool decided = false;
    for (std::size_t i = 0; i < s.expect.size(); ++i) {
      const auto k = s.expect[i].kind;
      if (k == ExpectKind::silence || k == ExpectKind::stream) break;
      if (seen.matched[i]) {
        decided = true;
        break;
      }
    }
    if (decided)
      settle_deadline =
          w_.now() + std::uint64_t{o_.settle_ms ? *o_.settle_ms : m_.settle_ms} * 1000;
  }
}

namespace {

// The longest time without a counted push: from `start` to the first, between
// two, and from the last to the end of the `window_ms` window.
std::uint64_t longest_gap(const std::vector<std::uint64_t>& times, std::uint64_t start,
                          std::uint32_t window_ms) {
  const std::uint64_t end = start + std::uint64_t{window_ms} * 1000;
  std::uint64_t gap = 0, prev = start;
  for (const std::uint64_t t : times) {
    gap = std::max(gap, t > prev ? t - prev : 0);
    prev = t;
  }
  return std::max(gap, end > prev ? end - prev : 0);
}

}  // namespace

StepResult CaseRunner::verdict(const Step& s, const Watch& seen) const {
  StepResult res;
  std::string near_miss = seen.near_miss;
  // The first alternative, in order, that holds.
  for (std::size_t i = 0; i < s.expect.size(); ++i) {
    const Expectation& e = s.expect[i];
    bool ok = false;
    std::string dev;
    switch (e.kind) {
      case ExpectKind::silence:
        ok = !seen.answered || seen.first_answer > seen.start + std::uint64_t{e.silence_ms} * 1000;
        if (!ok && near_miss.empty())
          near_miss = "expected silence for " + std::to_string(e.silence_ms) + " ms";
        break;
      case ExpectKind::stream: {
        const std::vector<std::uint64_t>& times = seen.push_times[i];
        const std::size_t n = times.size();
        double rate = 0;
        if (n >= 2)
          rate =
              static_cast<double>(n - 1) * 1e6 / static_cast<double>(times.back() - times.front());
        ok = n >= 2 && std::fabs(rate - e.rate_hz) <= e.tolerance * e.rate_hz;
        const std::uint64_t gap = longest_gap(times, seen.start, e.duration_ms);
        if (ok && e.max_gap_ms && gap > std::uint64_t{e.max_gap_ms} * 1000) {
          ok = false;
          char buf[160];
          std::snprintf(buf, sizeof buf, "%s stream: a gap of %.0f ms; at most %u ms expected",
                        e.ident.c_str(), static_cast<double>(gap) / 1000.0, e.max_gap_ms);
          near_miss = buf;
        } else if (ok && e.move_axis >= 0) {
          near_miss = short_of_motion(e, seen.angles[i]);
          ok = near_miss.empty();
        } else if (!ok) {
          char buf[160];
          std::snprintf(buf, sizeof buf,
                        "%s stream: %zu frame(s) in %u ms, %.2f Hz; expected %.2f Hz +-%.0f%%",
                        e.ident.c_str(), n, e.duration_ms, rate, e.rate_hz, e.tolerance * 100);
          if (near_miss.empty() || n > 0) near_miss = buf;
        }
        if (ok) dev = field_stream(m_.dialect, e.ident);
        break;
      }
      default:
        ok = seen.matched[i].has_value();
        if (ok) dev = frame_deviation(*seen.matched[i]);
        if (ok && dev.empty())
          if (const top::DeviceForm* rf = recorded_departure(m_, seen.matched[i]->frame);
              rf && rf->source == top::Source::field)
            dev = std::string(kFieldForm) + std::string(rf->evidence);
        if (ok && dev.empty()) dev = field_reply_form(m_, seen.matched[i]->frame);
        if (ok && seen.duplicate) dev = "the reply arrived more than once";
        break;
    }
    if (!ok) continue;
    if (e.tolerated) {
      res.outcome = Outcome::tolerated;
      res.reason = "only a tolerated alternative matched (" + std::string(to_string(e.kind)) +
                   (e.note.empty() ? "" : ": " + e.note) + ")";
    } else if (!dev.empty()) {
      res.outcome = Outcome::tolerated;
      res.reason = dev;
      res.field_form = dev.starts_with(kFieldForm);
    } else {
      res.outcome = Outcome::strict;
    }
    return res;
  }
  res.outcome = Outcome::fail;
  res.reason = !near_miss.empty() ? near_miss
               : seen.answered    ? "no alternative matched what the device sent"
                                  : "no answer within " + std::to_string(seen.window) + " ms";
  return res;
}

StepResult CaseRunner::run_readback(const Case& c, const Step& s, const std::string& sent,
                                    const top::Frame* rq, std::uint32_t timeout) {
  StepResult res;
  const Expectation& e = s.expect[0];
  w_.send(sent);
  // The write's answer (any frame of the identifier) first, where the
  // document gives the write one (top::write_reply); a write it gives none
  // is read back once the settle time has passed, answered or not.
  const top::CommandSpec* cmd =
      rq && rq->control == 'w' ? top::find_command(m_.dialect, rq->ident_view()) : nullptr;
  const bool unanswered = cmd && top::write_reply(*cmd) == top::WriteReply::nothing;
  Received r;
  std::uint64_t deadline =
      w_.now() + (unanswered ? std::uint64_t{o_.settle_ms ? *o_.settle_ms : m_.settle_ms}
                             : std::uint64_t{timeout}) *
                     1000;
  bool got = false;
  while (w_.next(deadline, r)) {
    if (rq && r.frame.ident_view() == rq->ident_view()) {
      got = true;
      break;
    }
    if (top::is_error_reply(r.frame.ident_view())) break;
  }
  if (!got && !unanswered) {
    res.reason = "the write got no answer, nothing to read back";
    return res;
  }
  if (!got)
    w_.note("the document gives " + std::string(rq->ident_view()) +
            " w no answer (top::write_reply): reading back");
  std::string read, err;
  if (!resolve_send(e.read, m_.dialect, t_.client_address(), read, err)) {
    res.outcome = Outcome::error;
    res.reason = err;
    return res;
  }
  w_.drain();
  w_.send(read);
  auto rp = top::parse_exact(read);
  const std::string want = e.data ? *e.data : rq ? std::string(rq->data()) : "";
  deadline = w_.now() + std::uint64_t{timeout_for(c, s)} * 1000;
  while (w_.next(deadline, r)) {
    if (rp.status != top::ParseStatus::frame || r.frame.ident_view() != rp.frame.ident_view())
      continue;
    if (!r.frame.ok()) {
      res.reason = "read-back reply has errors: " + r.frame.raw;
      return res;
    }
    if (r.frame.data() != want) {
      res.reason = "read back " + std::string(r.frame.data()) + ", wrote " + want;
      return res;
    }
    const std::string dev = frame_deviation(r);
    const bool swapped = r.frame.src == rp.frame.dst && r.frame.dst == rp.frame.src;
    res.outcome = dev.empty() && swapped && !e.tolerated ? Outcome::strict : Outcome::tolerated;
    res.reason = !dev.empty()  ? dev
                 : !swapped    ? "read-back reply does not swap the addresses"
                 : e.tolerated ? "only a tolerated alternative matched (readback)"
                               : "";
    res.field_form = dev.starts_with(kFieldForm);
    return res;
  }
  res.reason = "no answer to the read-back within " + std::to_string(timeout) + " ms";
  return res;
}

void CaseRunner::attempt(const Case& c, Verdict& v, std::string& reason, bool& field_form) {
  field_form = false;
  for (std::size_t i = 0; i < c.preconditions.size(); ++i) {
    StepResult sr = run_step(c, c.preconditions[i]);
    if (sr.outcome == Outcome::error) {
      v = Verdict::error;
      reason = sr.reason;
      return;
    }
    if (sr.outcome == Outcome::fail) {
      v = Verdict::inconclusive;
      reason = "precondition " + std::to_string(i + 1) + " not met: " + sr.reason;
      return;
    }
  }
  v = Verdict::pass;
  reason.clear();
  for (std::size_t i = 0; i < c.steps.size(); ++i) {
    StepResult sr = run_step(c, c.steps[i]);
    const std::string where = c.steps.size() > 1 ? "step " + std::to_string(i + 1) + ": " : "";
    if (sr.outcome == Outcome::error) {
      v = Verdict::error;
      reason = where + sr.reason;
      return;
    }
    if (sr.outcome == Outcome::fail) {
      v = Verdict::fail;
      reason = where + sr.reason;
      return;
    }
    if (sr.outcome == Outcome::tolerated && v == Verdict::pass) {
      v = Verdict::non_strict;
      reason = where + sr.reason;
      field_form = sr.field_form;
    } else if (sr.outcome == Outcome::tolerated && !sr.field_form) {
      field_form = false;
    }
  }
}

}  // namespace topconf::detail
