#include "conf/fuzz.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <thread>

#include "conf/link.hpp"
#include "conf/liveness.hpp"
#include "conf/probe.hpp"
#include "conf/runner.hpp"
#include "top/device.hpp"

namespace topconf {
namespace {

using WallClock = std::chrono::steady_clock;
using top::is_error_reply;

struct Session {
  const Matrix& m;
  Transport& t;
  const FuzzOptions& o;
  const CaseSource& src;
  FrameLink link;
  Probe probe, alt;  // the liveness probe, and a second sync frame
  std::uint64_t probes = 0;
  std::uint64_t t0 = 0;
  // Restarted, answering, no case since: a replay needs no second restart
  // (one that acts late, as `kill -HUP` can, would land mid-replay).
  bool fresh = false;

  std::uint64_t probe_timeout_us() const { return std::uint64_t{m.probe_timeout_ms} * 1000; }

  // One probe (up to `tries` times): any answer with its identifier, or
  // ERE, is life.
  bool alive(int tries) {
    for (int i = 0; i < tries; ++i) {
      ++probes;
      if (probe_once(link, probe, probe_timeout_us()) == ProbeHeard::answer) return true;
    }
    return false;
  }

  // Restart (when possible) and wait until the probe is answered again.
  bool revive(bool& restarted) {
    restarted = false;
    if (o.restart) restarted = o.restart();
    link.clear();
    const std::uint64_t deadline = link.now() + std::uint64_t{o.recover_ms} * 1000;
    do {
      if (alive(1)) {
        fresh = restarted;
        return true;
      }
    } while (link.now() < deadline);
    return false;
  }

  std::string check_reply(const FuzzCase& c, const Received& r) const {
    const top::Frame& f = r.frame;
    if (r.after_garbage) return "bytes that belong to no frame came before " + top::escape(f.raw);
    if (!f.ok()) {
      for (const auto& fd : f.findings)
        if (fd.severity == top::Severity::error)
          return "malformed reply " + top::escape(f.raw) + ": " +
                 std::string(top::to_string(fd.code)) + ": " + fd.message;
    }
    const char client = t.client_address();
    // To the client, or to whoever a request of the case came from
    // (reply_addressed: swapped, or in a recorded request order).
    bool addressed = f.dst == client && f.src != client;
    for (std::size_t i = 0; !addressed && i + 1 < c.addresses.size(); i += 2)
      addressed = reply_addressed(m.dialect, m.model, f, c.addresses[i], c.addresses[i + 1]);
    if (!addressed && f.src == client) {
      const top::DeviceForm* rf = recorded_form_of(m.dialect, m.model, f);
      addressed = rf && rf->order == top::Order::request_order;
    }
    if (!addressed)
      return "reply " + top::escape(f.raw) + " is addressed " + std::string(1, f.src) + " -> " +
             std::string(1, f.dst) + ", not to the client " + std::string(1, client);
    // An echo carries what the case sent: its values are the client's.
    const bool echo = f.ident_view() == c.ident && f.data_length > 0 &&
                      c.bytes.find(f.data()) != std::string::npos;
    if (echo || is_error_reply(f.ident_view())) return {};
    top::DecodeOptions dopt;
    dopt.dialect = m.dialect;
    dopt.model = m.model;
    dopt.role = top::Role::response;
    const top::Decoded dec = top::decode(f, dopt);
    if (!dec.command) return {};
    // (information is none: a length the field records, ArduPilot's 14-char FAI)
    for (const auto& fd : dec.findings)
      if (fd.severity != top::Severity::info &&
          (fd.code == top::FindingCode::value_out_of_range ||
           fd.code == top::FindingCode::bad_field || fd.code == top::FindingCode::data_length))
        return "reply " + top::escape(f.raw) + ": " + std::string(top::to_string(fd.code)) + ": " +
               fd.message;
    return {};
  }

  // Sends one case and classifies what comes back. False when the device
  // did not answer the sync probe after it (the caller checks liveness).
  bool run_one(const FuzzCase& c, FuzzCaseResult& r) {
    const bool sky = m.dialect == top::Dialect::skydroid;
    const std::uint64_t sent_at = link.now();
    r.start_us = sent_at - t0;
    link.send(c.bytes);
    std::vector<Received> got;
    Received rx;
    // The case's answer: its identifier or a recorded reply form of it (a
    // real SIP answers GIC with GIA), as the runner takes it.
    auto answers = [&](const top::Frame& f) {
      return !c.ident.empty() && top::answers_query(m.dialect, c.ident, f.ident_view());
    };
    auto own = [&](const top::Frame& f) { return answers(f) || is_error_reply(f.ident_view()); };
    // A datagram the kernel took before the case was sent (a late answer to
    // the case before it) is not this case's: neither its answer nor what
    // it drew, and no latency is measured to it.
    auto stale = [&](const Received& x) { return x.t_us < sent_at; };
    auto keep = [&](Received&& x) {
      if (stale(x) || (is_push(m.dialect, x.frame.ident_view()) && !answers(x.frame))) return;
      got.push_back(std::move(x));
    };
    if (!t.datagram() && c.open_end) {
      // The device holds the cut frame until its line is quiet (and 10 ms more).
      const std::uint64_t quiet = link.now() + std::uint64_t{top::quiet_line_ms} * 1000 + 10000;
      while (link.next(quiet, rx)) keep(std::move(rx));
    }
    bool found = false;
    std::uint64_t answered_at = 0;
    if (c.promise == Promise::answer || (c.promise == Promise::error && sky)) {
      const std::uint64_t deadline = sent_at + std::uint64_t{o.timeout_ms} * 1000;
      while (!found && link.next(deadline, rx)) {
        const bool mine = !stale(rx) && own(rx.frame);
        if (mine && !answered_at) answered_at = rx.t_us;
        keep(std::move(rx));
        found = mine;
      }
    }
    bool synced = true;
    if (!found) {
      // Sync: a probe the case does not contain; everything before its
      // answer belongs to the case.
      const Probe& p = c.bytes.find(probe.ident) == std::string::npos ? probe : alt;
      ++probes;
      link.send(p.bytes);
      synced = false;
      // Long enough to tell a slow answer from none.
      const std::uint64_t deadline =
          link.now() + std::max(probe_timeout_us(), std::uint64_t{o.slow_ms} * 1000 + 100000);
      while (link.next(deadline, rx)) {
        if (stale(rx)) continue;
        if (p.answered_by(rx.frame) && !is_error_reply(rx.frame) && rx.frame.ok() &&
            rx.frame.control == 'r') {
          synced = true;
          if (!answered_at) answered_at = rx.t_us;
          break;
        }
        if (own(rx.frame) && !answered_at) answered_at = rx.t_us;
        keep(std::move(rx));
      }
    }
    r.latency_us = answered_at ? answered_at - sent_at : 0;
    for (const Received& x : got) r.answers.push_back(x.frame.raw);
    if (!synced) return false;

    // Classify: the first class found wins, in the order of the enum.
    const bool promised = c.level != Level::may;
    bool answered_ident = false, answered_ere = false;
    for (const Received& x : got) {
      answered_ident |= answers(x.frame);
      answered_ere |= is_error_reply(x.frame.ident_view());
    }
    if (c.promise == Promise::silence && promised && (answered_ident || answered_ere)) {
      r.failure = FailureClass::accepted_corrupt;
      r.reason = "answered a frame with a bad checksum: " + top::escape(got.front().frame.raw);
      return true;
    }
    if (promised && c.promise == Promise::answer && !answered_ident) {
      r.failure = FailureClass::wrong_answer;
      r.reason = answered_ere ? "ERE where the document promises an answer (" +
                                    std::string(to_string(c.level)) + ")"
                              : "no answer where the document promises one (" +
                                    std::string(to_string(c.level)) + ")";
      return true;
    }
    if (promised && c.promise == Promise::error && answered_ident) {
      r.failure = FailureClass::wrong_answer;
      r.reason =
          "an answer where the document promises ERE (" + std::string(to_string(c.level)) + ")";
      return true;
    }
    for (const Received& x : got) {
      std::string why = check_reply(c, x);
      if (!why.empty()) {
        r.failure = FailureClass::bad_reply;
        r.reason = std::move(why);
        return true;
      }
    }
    if (r.latency_us > std::uint64_t{o.slow_ms} * 1000) {
      r.failure = FailureClass::slow;
      r.reason = "the first answer after the case took " + std::to_string(r.latency_us / 1000) +
                 " ms (--slow-ms " + std::to_string(o.slow_ms) + ")";
    }
    return true;
  }

  // Runs a case and the liveness check; sets a stopped failure.
  void run_checked(const FuzzCase& c, FuzzCaseResult& r, bool probe_now, bool& dead) {
    dead = false;
    fresh = false;
    bool ok = false;
    try {
      ok = run_one(c, r);
      if (ok && probe_now) ok = alive(1) || alive(2);
    } catch (const TransportError& e) {
      r.reason = e.what();
    }
    if (ok) return;
    const std::uint64_t lost = link.now();
    bool back = false;
    try {
      back = alive(3);
    } catch (const TransportError&) {
    }
    r.failure = FailureClass::stopped;
    const std::string why = r.reason.empty() ? "" : " (" + r.reason + ")";
    if (back) {
      r.reason = "no answer for " +
                 std::to_string((link.now() - lost) / 1000 + m.probe_timeout_ms) +
                 " ms after the case, then it answered again" + why;
    } else {
      dead = true;
      r.reason = "the device stopped answering after this case (the sync probe and 3 more of " +
                 std::to_string(m.probe_timeout_ms) + " ms unanswered)" + why;
    }
  }

  // Replays `cases` (after a restart when there is one): does the last one
  // fail with `cls` again?
  bool reproduces(const std::vector<FuzzCase>& cases, FailureClass cls) {
    bool restarted = false;
    if ((o.restart || cls == FailureClass::stopped) && !fresh) {
      if (!revive(restarted)) return false;
    }
    for (std::size_t i = 0; i < cases.size(); ++i) {
      FuzzCaseResult r;
      r.spec = cases[i];
      bool dead = false;
      run_checked(cases[i], r, true, dead);
      if (i + 1 == cases.size()) return r.failure == cls;
      if (dead) return false;
    }
    return false;
  }

  // After a failed case: revives the device when it stopped, minimises
  // the failure; false when the device did not answer again.
  bool after_failure(FuzzFailure& f, bool dead, const std::deque<FuzzCase>& recent) {
    bool alive_again = !dead;
    if (dead) alive_again = revive(f.restarted);
    if (alive_again && o.minimise) {
      minimise(f, std::vector<FuzzCase>(recent.begin(), recent.end()));
      bool restarted = false;
      // Leave the device answering for the cases that follow.
      if (!alive(1)) alive_again = revive(restarted);
    } else if (!alive_again) {
      f.how = MinimiseHow::skipped;
      f.note = o.restart ? "not minimised: the device did not answer again after the restart"
                         : "not minimised: no --restart-cmd, and the device did not answer "
                           "again";
    }
    return alive_again;
  }

  void minimise(FuzzFailure& f, const std::vector<FuzzCase>& window) {
    if (!o.restart && f.cls == FailureClass::stopped) {
      f.how = MinimiseHow::skipped;
      f.note = "not minimised: no --restart-cmd to bring the device back between replays";
      return;
    }
    if (reproduces({f.spec}, f.cls)) {
      f.how = MinimiseHow::alone;
      f.cases = {f.index};
      // One frame of the case that alone fails the same way.
      top::StreamDecoder dec;
      dec.feed(f.spec.bytes);
      dec.finish();
      std::vector<std::string> frames;
      top::StreamItem item;
      while (dec.next(item))
        if (item.kind == top::ItemKind::frame) frames.push_back(item.frame.raw);
      if (frames.size() == 1 && frames[0] == f.spec.bytes) {
        f.frame = frames[0];
        f.note = "reproduces alone after a restart; the case is one frame";
        return;
      }
      for (const std::string& fr : frames) {
        FuzzCase one = f.spec;
        one.bytes = fr;
        src.judge(one);
        if (f.spec.mutated && one.promise != Promise::silence) one.promise = Promise::none;
        if (reproduces({one}, f.cls)) {
          f.frame = fr;
          f.note = "reproduces alone after a restart; shrunk to one frame of the case";
          return;
        }
      }
      f.note = "reproduces alone after a restart; no single frame of it does";
      return;
    }
    std::vector<FuzzCase> w = window;
    w.push_back(f.spec);
    if (w.size() > 1 && reproduces(w, f.cls)) {
      // Drop every earlier case the failure does not need.
      for (std::size_t i = 0; i + 1 < w.size();) {
        std::vector<FuzzCase> less = w;
        less.erase(less.begin() + static_cast<std::ptrdiff_t>(i));
        if (reproduces(less, f.cls))
          w = std::move(less);
        else
          ++i;
      }
      f.how = MinimiseHow::window;
      f.cases.clear();
      for (const auto& c : w) f.cases.push_back(c.index);
      f.note = "does not fail alone; fails after " + std::to_string(w.size() - 1) +
               " earlier case(s) of the window";
      return;
    }
    f.how = MinimiseHow::not_reproduced;
    f.note = "did not fail again, alone or after the " + std::to_string(window.size()) +
             " case(s) before it";
  }
};

// The probe, the first the device answers (conf/liveness.hpp: the matrix's,
// else the catalog's for the model), and a second sync frame for cases that
// contain the probe's identifier: the first must-level read of the matrix
// with another one.
ProbeChoice set_probes(const Matrix& m, Transport& t, Session& s) {
  const ProbeChoice choice =
      choose_probe(probes_for(m, t.client_address()), 3, [&](const Probe& p) {
        ++s.probes;
        return probe_once(s.link, p, s.probe_timeout_us());
      });
  if (!choice.probe) return choice;
  s.probe = *choice.probe;
  s.alt = s.probe;
  std::string err;
  for (const Case& k : m.cases) {
    if (k.level != Level::must || !k.applies_to(m.model) || k.steps.size() != 1 ||
        !k.steps[0].send || k.steps[0].send->raw || k.steps[0].send->control != 'r' ||
        k.steps[0].send->command == s.probe.ident ||
        std::find(k.tags.begin(), k.tags.end(), "read") == k.tags.end())
      continue;
    std::string b;
    if (resolve_send(*k.steps[0].send, m.dialect, t.client_address(), b, err) &&
        b.size() > top::prefix_size) {
      s.alt = Probe::of(b, false);
      break;
    }
  }
  return choice;
}

}  // namespace

int FuzzResult::exit_code() const noexcept {
  if (unusable) return 2;
  return failures.empty() && !aborted ? 0 : 1;
}

FuzzResult run_fuzz(const Matrix& m, Transport& t, const FuzzOptions& o) {
  FuzzResult res;
  res.target = t.describe();
  res.model = m.model;
  res.seed = o.seed;
  res.started_at = iso_now();
  const auto wall0 = WallClock::now();
  auto finish = [&] {
    res.seconds = std::chrono::duration<double>(WallClock::now() - wall0).count();
  };
  const CaseSource src(m.model, t.client_address(), o.seed, &m);
  res.catalog_cases = src.catalog_cases();
  Session s{m, t, o, src, FrameLink(t, o.pcap, 4096), {}, {}, 0, t.now_us()};
  // the copies of a device's datagrams are one datagram (top/device.hpp fan_out)
  s.link.accept_copies(sends_copies(m.model));

  try {
    const ProbeChoice choice = set_probes(m, t, s);
    res.probe_note = choice.note();
    if (!choice.probe) {
      res.unusable = true;
      res.unusable_reason = t.describe() + ": " +
                            (choice.heard ? "answered none of the liveness probes, " + choice.note()
                                          : "no frame came back to the liveness probes") +
                            " (3 tries each, " + std::to_string(m.probe_timeout_ms) + " ms each)";
    }
  } catch (const TransportError& e) {
    res.unusable = true;
    res.unusable_reason = e.what();
  }
  if (res.unusable) {
    finish();
    return res;
  }

  std::deque<FuzzCase> recent;
  std::uint64_t n = 0, index = o.start;
  std::size_t next_only = 0;
  auto last_progress = wall0;
  res.next_index = o.start;
  for (;;) {
    if (!o.only.empty()) {
      if (next_only >= o.only.size()) break;
      index = o.only[next_only++];
    } else if (o.end && index >= *o.end) {
      break;
    }
    const auto now = WallClock::now();
    if (o.duration_s > 0 && std::chrono::duration<double>(now - wall0).count() >= o.duration_s)
      break;
    if (o.rate > 0) {
      const auto due = wall0 + std::chrono::duration_cast<WallClock::duration>(
                                   std::chrono::duration<double>(static_cast<double>(n) / o.rate));
      if (due > now) std::this_thread::sleep_until(due);
    }
    FuzzCaseResult r;
    r.spec = src.at(index);
    bool dead = false;
    const bool probe_now = o.probe_every <= 1 || (n + 1) % o.probe_every == 0;
    s.run_checked(r.spec, r, probe_now, dead);
    ++n;
    res.cases_run = n;
    res.next_index = index + 1;
    if (o.on_case) o.on_case(r);
    if (r.failure) {
      FuzzFailure f;
      f.index = index;
      f.cls = *r.failure;
      f.reason = r.reason;
      f.spec = r.spec;
      for (const auto& c : recent) f.before.push_back(c.index);
      const bool alive_again = s.after_failure(f, dead, recent);
      if (o.on_failure) o.on_failure(f);
      res.failures.push_back(std::move(f));
      if (!alive_again) {
        res.aborted = true;
        res.aborted_reason = "the device stopped answering at case " + std::to_string(index) +
                             " and did not answer again within " + std::to_string(o.recover_ms) +
                             " ms";
        break;
      }
      recent.clear();
      if (o.max_failures && res.failures.size() >= o.max_failures) {
        if (o.only.empty()) ++index;
        break;
      }
    } else {
      recent.push_back(r.spec);
      if (recent.size() > o.window) recent.pop_front();
    }
    if (o.only.empty()) ++index;
    if (o.on_progress && WallClock::now() - last_progress >= std::chrono::seconds(1)) {
      last_progress = WallClock::now();
      o.on_progress(n,
                    std::chrono::duration<double>(last_progress - wall0).count() > 0
                        ? static_cast<double>(n) /
                              std::chrono::duration<double>(last_progress - wall0).count()
                        : 0,
                    res.failures.size());
    }
  }
  res.probes = s.probes;
  finish();
  return res;
}

}  // namespace topconf
