#include "conf/runner.hpp"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <random>

#include "conf/link.hpp"
#include "conf/liveness.hpp"
#include "conf/probe.hpp"
#include "steps.hpp"
#include "top/enum_names.hpp"
#include "wire.hpp"

namespace topconf {

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

namespace {

using detail::CaseRunner;
using detail::Wire;

// The matrix's cases that --case, --tag and --level select, in the order
// --seed shuffles them into.
std::vector<const Case*> select_cases(const Matrix& m, const RunOptions& o, RunResult& res) {
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
  return order;
}

// The liveness probe, up to `tries` times (true without one: the device
// answered none, conf/liveness.hpp).
bool alive(const std::optional<Probe>& p, Wire& w, int tries) {
  if (!p) return true;
  for (int i = 0; i < tries; ++i)
    if (w.probe(*p) == ProbeHeard::answer) return true;
  return false;
}

// The retry loop of one case, then the liveness probe after it; `dead`
// is set once the device stopped answering.
void run_case(const Matrix& m, const std::optional<Probe>& probe, const RunOptions& o, Wire& w,
              CaseRunner& run, const Case& c, CaseResult& cr, std::string& dead) {
  const std::uint32_t retries = o.retries        ? *o.retries
                                : c.retries >= 0 ? static_cast<std::uint32_t>(c.retries)
                                                 : m.retries;
  bool failed_once = false;
  for (std::uint32_t a = 0; a <= retries; ++a) {
    ++cr.attempts;
    if (a > 0) w.note("retry " + std::to_string(a) + " of " + std::to_string(retries));
    try {
      run.attempt(c, cr.verdict, cr.reason, cr.field_form);
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
  bool ok = true;
  try {
    ok = alive(probe, w, 5);
  } catch (const TransportError&) {
    ok = false;
  }
  if (!ok) {
    dead = "the device stopped answering after case " + c.id + " (liveness probe failed)";
    w.note(dead);
  }
}

}  // namespace

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
  CaseRunner run(m, t, o, w);
  const std::vector<const Case*> order = select_cases(m, o, res);

  auto finish = [&] {
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  };
  std::optional<Probe> probe;
  try {
    const std::vector<Probe> probes = probes_for(m, t.client_address());
    const ProbeChoice choice = choose_probe(probes, 3, [&](const Probe& p) { return w.probe(p); });
    res.probe_note = choice.note();
    probe = choice.probe;
    if (!probes.empty() && !choice.heard) {
      std::string names;
      for (const Probe& p : probes) names += (names.empty() ? "" : ", ") + p.ident;
      res.unreachable = true;
      res.unreachable_reason = t.describe() + ": no frame came back to the liveness probe " +
                               names + " (3 tries each, " + std::to_string(m.probe_timeout_ms) +
                               " ms each)";
      finish();
      return res;
    }
    if (!probes.empty() && !probe)
      res.probe_note += " (the device sends other frames: no liveness check between cases)";
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
      run_case(m, probe, o, w, run, *c, cr, dead);
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
