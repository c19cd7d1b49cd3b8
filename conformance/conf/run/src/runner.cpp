#include "conf/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <deque>
#include <iterator>
#include <random>
#include <regex>

#include "conf/link.hpp"
#include "top/enum_names.hpp"

namespace topconf {

std::string iso_now() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[40];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  char out[48];
  std::snprintf(out, sizeof out, "%s.%03dZ", buf, static_cast<int>(ms));
  return out;
}

namespace {

// The runner's side of the link: frames, and the case's transcript.
class Wire {
 public:
  Wire(Transport& t, const Matrix& m, const RunOptions& o, std::uint64_t t0)
      : link_(t, o.pcap, o.max_frames_per_step), m_(m), o_(o), t0_(t0) {
    link_.on_chunk = [this](std::string_view chunk) { log('<', std::string(chunk)); };
    link_.on_garbage = [this](std::size_t n) {
      note("garbage: " + std::to_string(n) + " byte(s) that belong to no frame");
    };
  }

  Wire(const Wire&) = delete;  // the link calls back into this one
  Wire& operator=(const Wire&) = delete;

  void begin_case(CaseResult* r) { rec_ = r; }
  std::uint64_t now() { return link_.now(); }

  void note(std::string s) { log('!', std::move(s)); }

  void send(std::string_view bytes) {
    log('>', std::string(bytes));
    link_.send(bytes);
  }

  // Next frame before `deadline`; false on timeout. Garbage is noted.
  bool next(std::uint64_t deadline, Received& out) { return link_.next(deadline, out); }

  // Discards whatever already arrived (late answers of a previous step).
  void drain() {
    Received r;
    const std::uint64_t d = now();
    std::size_t n = 0, late = 0;
    while (n < o_.max_frames_per_step && next(d, r)) {
      ++n;
      const std::string_view id = r.frame.ident_view();
      if (!is_push(m_.dialect, id)) ++late;  // pushes (GAC, GIC) are expected
    }
    link_.clear();
    if (late > 0)
      note("discarded " + std::to_string(late) + " late frame(s) before the next exchange");
  }

 private:
  void log(char dir, std::string bytes) {
    if (!rec_) return;
    if (rec_->transcript.size() >= o_.max_transcript) {
      ++rec_->dropped_exchanges;
      return;
    }
    if (bytes.size() > 512) bytes = bytes.substr(0, 512) + "...";
    rec_->transcript.push_back(Exchange{now() - t0_, dir, std::move(bytes)});
  }

  FrameLink link_;
  const Matrix& m_;
  const RunOptions& o_;
  std::uint64_t t0_;
  CaseResult* rec_ = nullptr;
};

enum class Outcome : std::uint8_t { strict, tolerated, fail, error };

struct StepResult {
  Outcome outcome = Outcome::fail;
  std::string reason;
  bool field_form = false;  // tolerated only for a form the field records
};

constexpr std::string_view kFieldForm = "the field's form, not the document's: ";

// The recorded form (top/device.hpp) a device frame matches where it departs
// from the document's rule (the request's address order, another header),
// or nullptr.
const top::DeviceForm* recorded_departure(const Matrix& m, const top::Frame& f) {
  const top::Sent sent = is_push(m.dialect, f.ident_view()) ? top::Sent::push : top::Sent::reply;
  const top::DeviceForm* rf = top::recorded_form(m.dialect, m.model, f, sent);
  if (!rf) return nullptr;
  const top::CommandSpec* cmd = top::find_command(m.dialect, f.ident_view());
  const bool rule =
      rf->order == top::Order::swapped &&
      rf->header == top::choose_header(m.dialect, cmd ? cmd->address : 'G', f.data_length);
  return rule ? nullptr : rf;
}

// A deviation that a strict match must not have: a warning or error at the
// frame level, or a named firmware quirk.
std::string frame_deviation(const Received& r) {
  if (r.after_garbage) return "garbage preceded the frame";
  for (const auto& f : r.frame.findings) {
    if (f.severity == top::Severity::error || f.severity == top::Severity::warning ||
        !f.quirk.empty() || f.code == top::FindingCode::tmp_quirk)
      return std::string(top::to_string(f.code)) + ": " + f.message;
  }
  return {};
}

struct Runner {
  const Matrix& m;
  Transport& t;
  const RunOptions& o;
  Wire& w;

  std::uint32_t timeout_for(const Case& c, const Step& s) const {
    if (o.timeout_ms) return *o.timeout_ms;
    if (s.timeout_ms) return s.timeout_ms;
    if (c.timeout_ms) return c.timeout_ms;
    return m.timeout_ms;
  }

  bool addresses_ok(const Expectation& e, const top::Frame* req, const top::Frame& f) const {
    if (e.any_addresses || !req) return true;
    if (f.src == req->dst && f.dst == req->src) return true;
    // A recorded form in the request's order (the SkyDroid 4.22 SLR example).
    const top::DeviceForm* rf = recorded_departure(m, f);
    return rf && rf->order == top::Order::request_order && f.src == req->src && f.dst == req->dst;
  }

  // Does `r` satisfy a frame-type alternative? `why` collects near misses.
  bool matches(const Expectation& e, const top::Frame* req, const std::string& exact,
               const Received& r, std::string& why) const {
    const top::Frame& f = r.frame;
    if (!f.ok()) {
      why = "a frame arrived with errors: " +
            (f.findings.empty() ? std::string("?") : f.findings[0].message);
      return false;
    }
    switch (e.kind) {
      case ExpectKind::frame:
        if (f.raw == exact) return true;
        why = "got " + f.raw + ", expected " + exact;
        return false;
      case ExpectKind::echo:
        if (!req) return false;
        if (f.ident_view() != req->ident_view()) return false;
        if (f.control != req->control || f.data() != req->data()) {
          why = "reply " + f.raw + " is not an echo of " + req->raw;
          return false;
        }
        if (!addresses_ok(e, req, f)) {
          why = "echo " + f.raw + " does not swap the addresses";
          return false;
        }
        return true;
      case ExpectKind::error:
        if (f.ident_view() != "ERE") {
          if (req && f.ident_view() == req->ident_view())
            why = "answered " + f.raw + " instead of ERE";
          return false;
        }
        if (!addresses_ok(e, req, f)) {
          why = "ERE " + f.raw + " does not swap the addresses";
          return false;
        }
        return true;
      case ExpectKind::reply: {
        const std::string ident = !e.ident.empty() ? e.ident
                                  : req            ? std::string(req->ident_view())
                                                   : "";
        if (f.ident_view() != ident) {
          if (f.ident_view() == "ERE") why = "the device answered ERE";
          return false;
        }
        if (e.control && f.control != e.control) {
          why = "reply " + f.raw + " has control '" + std::string(1, f.control ? f.control : '?') +
                "'";
          return false;
        }
        if (!addresses_ok(e, req, f)) {
          why = "reply " + f.raw + " does not swap the addresses";
          return false;
        }
        const std::string data(f.data());
        if (e.data && data != *e.data) {
          why = "data " + data + ", expected " + *e.data;
          return false;
        }
        if (!e.data_pattern.empty() && !std::regex_match(data, std::regex(e.data_pattern))) {
          why = "data " + data + " does not match /" + e.data_pattern + "/";
          return false;
        }
        top::DecodeOptions dopt;
        dopt.dialect = m.dialect;
        dopt.model = m.model;
        dopt.role = top::Role::response;
        top::Decoded dec = top::decode(f, dopt);
        if (dec.command) {
          for (const auto& fd : dec.findings) {
            if (fd.severity != top::Severity::warning) continue;
            if (fd.code == top::FindingCode::unswapped_addresses) continue;
            why =
                "reply " + f.raw + ": " + std::string(top::to_string(fd.code)) + ": " + fd.message;
            return false;
          }
        }
        for (const FieldCheck& fc : e.fields) {
          const top::FieldValue* fv = nullptr;
          for (const auto& x : dec.fields)
            if (x.name() == fc.name) fv = &x;
          if (!fv || !fv->valid) {
            why = "reply " + f.raw + " has no valid field " + fc.name;
            return false;
          }
          const std::string raw = f.raw.substr(fv->offset, fv->length);
          if ((fc.min && fv->value < *fc.min) || (fc.max && fv->value > *fc.max)) {
            why = "field " + fc.name + " = " + top::format_value(*fv) + " is out of range";
            return false;
          }
          if (!fc.enums.empty() && std::find(fc.enums.begin(), fc.enums.end(),
                                             std::string(fv->enum_name)) == fc.enums.end()) {
            why = "field " + fc.name + " = " + top::format_value(*fv) + " is not an allowed value";
            return false;
          }
          if (!fc.pattern.empty() && !std::regex_match(raw, std::regex(fc.pattern))) {
            why = "field " + fc.name + " = " + raw + " does not match /" + fc.pattern + "/";
            return false;
          }
          if (fc.equals && raw != *fc.equals) {
            why = "field " + fc.name + " = " + raw + ", expected " + *fc.equals;
            return false;
          }
        }
        return true;
      }
      default:
        return false;
    }
  }

  StepResult run_step(const Case& c, const Step& s) {
    StepResult res;
    w.drain();
    const std::uint32_t timeout = timeout_for(c, s);
    std::string sent;
    std::optional<top::Frame> req;
    if (s.send) {
      std::string err;
      if (!resolve_send(*s.send, m.dialect, t.client_address(), sent, err)) {
        res.outcome = Outcome::error;
        res.reason = "cannot build the frame: " + err;
        return res;
      }
      auto p = top::parse_exact(sent);
      if (p.status == top::ParseStatus::frame) req = p.frame;
    }
    const top::Frame* rq = req ? &*req : nullptr;
    // Exact frames of the alternatives, resolved once.
    std::vector<std::string> exact(s.expect.size());
    for (std::size_t i = 0; i < s.expect.size(); ++i) {
      if (s.expect[i].kind == ExpectKind::frame) {
        std::string err;
        resolve_send(s.expect[i].frame, m.dialect, t.client_address(), exact[i], err);
      }
    }
    // Readback is a dialogue of its own.
    if (s.expect.size() >= 1 && s.expect[0].kind == ExpectKind::readback)
      return run_readback(c, s, sent, rq, timeout);

    bool has_frame_alt = false;
    std::uint32_t silence_ms = 0, stream_ms = 0;
    for (const auto& e : s.expect) {
      if (e.kind == ExpectKind::silence) {
        silence_ms = std::max(silence_ms, e.silence_ms);
      } else if (e.kind == ExpectKind::stream) {
        stream_ms = std::max(stream_ms, e.duration_ms);
      } else if (e.kind != ExpectKind::readback)
        has_frame_alt = true;
    }
    if (s.send) w.send(sent);
    const std::uint64_t start = w.now();
    std::uint64_t window = has_frame_alt ? timeout : 0;
    window = std::max<std::uint64_t>(window, silence_ms);
    window = std::max<std::uint64_t>(window, stream_ms);
    const std::uint64_t deadline = start + window * 1000;

    std::vector<std::optional<Received>> matched(s.expect.size());
    std::vector<std::uint64_t> push_times;  // per stream ident
    std::string stream_ident;
    for (const auto& e : s.expect)
      if (e.kind == ExpectKind::stream) stream_ident = e.ident;
    std::uint64_t first_answer = 0;  // time of the first non-push frame
    bool answered = false;
    std::string near_miss;
    std::size_t frames = 0;
    bool duplicate = false;
    std::uint64_t settle_deadline = 0;
    Received r;
    for (;;) {
      const std::uint64_t dl = settle_deadline ? std::min(settle_deadline, deadline) : deadline;
      if (!w.next(dl, r)) break;
      if (++frames > o.max_frames_per_step) {
        w.note("more than " + std::to_string(o.max_frames_per_step) +
               " frames in one step: flooding");
        break;
      }
      const std::string_view id = r.frame.ident_view();
      if (!stream_ident.empty() && id == stream_ident && r.frame.ok() &&
          r.t_us <= start + stream_ms * 1000)
        push_times.push_back(r.t_us);
      const bool push = is_push(m.dialect, id) && !(rq && rq->ident_view() == id);
      if (!push && !answered) {
        answered = true;
        first_answer = r.t_us;
      }
      if (settle_deadline) {
        // Watching for duplicates of the reply that matched.
        for (const auto& mm : matched)
          if (mm && mm->frame.raw == r.frame.raw) duplicate = true;
        continue;
      }
      for (std::size_t i = 0; i < s.expect.size(); ++i) {
        const auto k = s.expect[i].kind;
        if (matched[i] || k == ExpectKind::silence || k == ExpectKind::stream) continue;
        std::string why;
        if (matches(s.expect[i], rq, exact[i], r, why))
          matched[i] = r;
        else if (!why.empty() && near_miss.empty())
          near_miss = why;
      }
      // Stop early when the first alternative that can still decide did.
      bool decided = false;
      for (std::size_t i = 0; i < s.expect.size(); ++i) {
        const auto k = s.expect[i].kind;
        if (k == ExpectKind::silence || k == ExpectKind::stream) break;
        if (matched[i]) {
          decided = true;
          break;
        }
      }
      if (decided)
        settle_deadline = w.now() + std::uint64_t{o.settle_ms ? *o.settle_ms : m.settle_ms} * 1000;
    }
    // The verdict: the first alternative, in order, that holds.
    for (std::size_t i = 0; i < s.expect.size(); ++i) {
      const Expectation& e = s.expect[i];
      bool ok = false;
      std::string dev;
      switch (e.kind) {
        case ExpectKind::silence:
          ok = !answered || first_answer > start + std::uint64_t{e.silence_ms} * 1000;
          if (!ok && near_miss.empty())
            near_miss = "expected silence for " + std::to_string(e.silence_ms) + " ms";
          break;
        case ExpectKind::stream: {
          const std::size_t n = push_times.size();
          double rate = 0;
          if (n >= 2)
            rate = static_cast<double>(n - 1) * 1e6 /
                   static_cast<double>(push_times.back() - push_times.front());
          ok = n >= 2 && std::fabs(rate - e.rate_hz) <= e.tolerance * e.rate_hz;
          if (!ok) {
            char buf[160];
            std::snprintf(buf, sizeof buf,
                          "%s stream: %zu frame(s) in %u ms, %.2f Hz; expected %.2f Hz +-%.0f%%",
                          e.ident.c_str(), n, e.duration_ms, rate, e.rate_hz, e.tolerance * 100);
            if (near_miss.empty() || n > 0) near_miss = buf;
          }
          break;
        }
        default:
          ok = matched[i].has_value();
          if (ok) dev = frame_deviation(*matched[i]);
          if (ok && dev.empty())
            if (const top::DeviceForm* rf = recorded_departure(m, matched[i]->frame);
                rf && rf->source == top::Source::field)
              dev = std::string(kFieldForm) + std::string(rf->evidence);
          if (ok && duplicate) dev = "the reply arrived more than once";
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
                 : answered         ? "no alternative matched what the device sent"
                                    : "no answer within " + std::to_string(window) + " ms";
    return res;
  }

  StepResult run_readback(const Case& c, const Step& s, const std::string& sent,
                          const top::Frame* rq, std::uint32_t timeout) {
    StepResult res;
    const Expectation& e = s.expect[0];
    w.send(sent);
    // The write's answer (any frame of the identifier) first.
    Received r;
    std::uint64_t deadline = w.now() + std::uint64_t{timeout} * 1000;
    bool got = false;
    while (w.next(deadline, r)) {
      if (rq && r.frame.ident_view() == rq->ident_view()) {
        got = true;
        break;
      }
      if (r.frame.ident_view() == "ERE") break;
    }
    if (!got) {
      res.reason = "the write got no answer, nothing to read back";
      return res;
    }
    std::string read, err;
    if (!resolve_send(e.read, m.dialect, t.client_address(), read, err)) {
      res.outcome = Outcome::error;
      res.reason = err;
      return res;
    }
    w.drain();
    w.send(read);
    auto rp = top::parse_exact(read);
    const std::string want = e.data ? *e.data : rq ? std::string(rq->data()) : "";
    deadline = w.now() + std::uint64_t{timeout_for(c, s)} * 1000;
    while (w.next(deadline, r)) {
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
      return res;
    }
    res.reason = "no answer to the read-back within " + std::to_string(timeout) + " ms";
    return res;
  }

  // Runs the case once: preconditions then steps.
  void attempt(const Case& c, Verdict& v, std::string& reason, bool& field_form) {
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

  bool probe(int tries) {
    if (!m.probe) return true;
    std::string bytes, err;
    if (!resolve_send(*m.probe, m.dialect, t.client_address(), bytes, err)) return true;
    auto pr = top::parse_exact(bytes);
    const bool parsed = pr.status == top::ParseStatus::frame;
    const std::string ident = parsed ? std::string(pr.frame.ident_view()) : "";
    const char control = parsed ? pr.frame.control : 0;
    for (int i = 0; i < tries; ++i) {
      w.drain();
      w.send(bytes);
      Received r;
      const std::uint64_t deadline = w.now() + std::uint64_t{m.probe_timeout_ms} * 1000;
      // Alive: the probe was answered (even with a damaged frame, or ERE).
      // Attitude pushes do not count: a hung device may still stream.
      while (w.next(deadline, r)) {
        const std::string_view id = r.frame.ident_view();
        if ((id == ident && r.frame.control == control) || id == "ERE") {
          w.drain();
          return true;
        }
      }
    }
    return false;
  }
};

}  // namespace

namespace {
constexpr std::string_view kVerdict[] = {"pass", "non-strict",   "fail",
                                         "n/a",  "inconclusive", "error"};
static_assert(std::size(kVerdict) == static_cast<std::size_t>(Verdict::error) + 1);
}  // namespace

std::string_view to_string(Verdict v) noexcept { return top::enum_name(kVerdict, v); }

bool glob_match(std::string_view p, std::string_view s) noexcept {
  std::size_t pi = 0, si = 0, star = std::string_view::npos, mark = 0;
  while (si < s.size()) {
    if (pi < p.size() && (p[pi] == '?' || p[pi] == s[si])) {
      ++pi;
      ++si;
    } else if (pi < p.size() && p[pi] == '*') {
      star = pi++;
      mark = si;
    } else if (star != std::string_view::npos) {
      pi = star + 1;
      si = ++mark;
    } else
      return false;
  }
  while (pi < p.size() && p[pi] == '*') ++pi;
  return pi == p.size();
}

std::size_t RunResult::count(Verdict v) const noexcept {
  return static_cast<std::size_t>(std::count_if(
      cases.begin(), cases.end(), [v](const CaseResult& c) { return c.verdict == v; }));
}

int RunResult::exit_code() const noexcept {
  if (unreachable) return 2;
  for (const auto& c : cases) {
    if (!c.spec || c.spec->level == Level::may) continue;
    if (c.verdict == Verdict::non_strict && c.field_form) continue;
    if (c.verdict != Verdict::pass && c.verdict != Verdict::not_applicable) return 1;
  }
  return 0;
}

RunResult run_matrix(const Matrix& matrix, Transport& t, const RunOptions& o) {
  RunResult res;
  // The result keeps its own copy, so it outlives the caller's matrix.
  res.matrix = std::make_shared<const Matrix>(matrix);
  const Matrix& m = *res.matrix;
  res.target = t.describe();
  res.matrix_file = m.file;
  res.model = m.model;
  res.started_at = iso_now();
  const auto wall0 = std::chrono::steady_clock::now();
  const std::uint64_t t0 = t.now_us();
  Wire w(t, m, o, t0);
  Runner run{m, t, o, w};

  std::vector<const Case*> order;
  for (const auto& c : m.cases) {
    if (!o.cases.empty() && std::none_of(o.cases.begin(), o.cases.end(),
                                         [&](const std::string& g) { return glob_match(g, c.id); }))
      continue;
    if (!o.tags.empty() && std::none_of(o.tags.begin(), o.tags.end(), [&](const std::string& tg) {
          return std::find(c.tags.begin(), c.tags.end(), tg) != c.tags.end();
        }))
      continue;
    if (!o.levels.empty() && std::find(o.levels.begin(), o.levels.end(), c.level) == o.levels.end())
      continue;
    order.push_back(&c);
  }
  if (o.seed) {
    res.seed = *o.seed;
    res.seeded = true;
    std::mt19937_64 rng(*o.seed);
    std::shuffle(order.begin(), order.end(), rng);
  }

  auto finish = [&] {
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  };
  try {
    if (!run.probe(3)) {
      res.unreachable = true;
      res.unreachable_reason = t.describe() + ": no answer to the liveness probe (3 tries, " +
                               std::to_string(m.probe_timeout_ms) + " ms each)";
      finish();
      return res;
    }
  } catch (const TransportError& e) {
    res.unreachable = true;
    res.unreachable_reason = e.what();
    finish();
    return res;
  }

  std::string dead;  // set once the device stopped answering
  for (const Case* c : order) {
    CaseResult cr;
    cr.spec = c;
    cr.started_at = iso_now();
    cr.start_us = t.now_us() - t0;
    w.begin_case(&cr);
    if (!c->applies_to(m.model)) {
      cr.verdict = Verdict::not_applicable;
      cr.reason = "the case does not apply to " + std::string(top::to_string(m.model));
    } else if (!dead.empty()) {
      cr.verdict = Verdict::error;
      cr.reason = dead;
    } else {
      const std::uint32_t retries = o.retries         ? *o.retries
                                    : c->retries >= 0 ? static_cast<std::uint32_t>(c->retries)
                                                      : m.retries;
      bool failed_once = false;
      for (std::uint32_t a = 0; a <= retries; ++a) {
        ++cr.attempts;
        if (a > 0) w.note("retry " + std::to_string(a) + " of " + std::to_string(retries));
        try {
          run.attempt(*c, cr.verdict, cr.reason, cr.field_form);
        } catch (const TransportError& e) {
          cr.verdict = Verdict::error;
          cr.reason = e.what();
        }
        if (cr.verdict == Verdict::fail || cr.verdict == Verdict::error) {
          failed_once = true;
          continue;
        }
        break;
      }
      if (failed_once && (cr.verdict == Verdict::pass || cr.verdict == Verdict::non_strict)) {
        cr.flaky = true;
        cr.reason = (cr.reason.empty() ? "" : cr.reason + "; ") + "flaky: passed on attempt " +
                    std::to_string(cr.attempts);
      }
      // Liveness between cases.
      bool alive = true;
      try {
        alive = run.probe(5);
      } catch (const TransportError& e) {
        alive = false;
      }
      if (!alive) {
        dead = "the device stopped answering after case " + c->id + " (liveness probe failed)";
        w.note(dead);
      }
    }
    cr.duration_us = t.now_us() - t0 - cr.start_us;
    w.begin_case(nullptr);
    if (o.on_case) o.on_case(cr);
    res.cases.push_back(std::move(cr));
  }
  finish();
  return res;
}

}  // namespace topconf
