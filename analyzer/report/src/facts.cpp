// topdump report: the ranked one-line facts at the top of the report.
#include <algorithm>
#include <cmath>
#include <map>

#include "diagnoses/cause.hpp"
#include "report/analysis.hpp"
#include "report/report.hpp"

namespace topdump::report {

std::optional<std::size_t> unanswered_rank(Cause c) noexcept {
  if (diagnosis_of(c)) return std::nullopt;
  const auto* at = std::find(kUnansweredOrder.begin(), kUnansweredOrder.end(), c);
  if (at == kUnansweredOrder.end()) return std::nullopt;
  return static_cast<std::size_t>(at - kUnansweredOrder.begin());
}

namespace {

void add(Report& rep, int rank, top::Severity s, std::string text, std::string anchor) {
  rep.facts.push_back({rank, s, std::move(text), std::move(anchor)});
}

// Unanswered requests, grouped by identifier and cause (a cause that is a
// diagnosis is that diagnosis's item: diagnosis_facts).
void unanswered_facts(const ReportSink& d, Report& rep) {
  struct Group {
    std::uint64_t n = 0;
    std::int64_t first = kNoTime, last = kNoTime;
  };
  // by identifier, then the cause's place in kUnansweredOrder
  std::map<std::pair<std::string_view, std::size_t>, Group> groups;
  for (const auto& u : d.unanswered) {
    const std::optional<std::size_t> rank = unanswered_rank(u.cause);
    if (!rank) continue;
    Group& g = groups[{u.ident, *rank}];
    ++g.n;
    if (g.first == kNoTime) g.first = u.ts;
    g.last = u.ts;
  }
  for (const auto& [k, g] : groups) {
    const Cause cause = kUnansweredOrder[k.second];
    std::string t = std::to_string(g.n) + " " + std::string(k.first) +
                    (g.n == 1 ? " request unanswered at " + clock_text(g.first)
                              : " requests unanswered from " + clock_text(g.first) + " to " +
                                    clock_text(g.last)) +
                    ": ";
    if (cause == Cause::none)
      t += "no response";
    else
      t += describe(cause);  // the cause for people, from its value
    add(rep, cause == Cause::none ? 80 : 60,
        cause == Cause::other_port ? top::Severity::info : top::Severity::warning, std::move(t),
        "unanswered");
  }
}

// The diagnoses the session reported (streams off their rate or stalled,
// silent devices, dropped requests...): one item each, with its code.
void diagnosis_facts(const ReportSink& d, Report& rep) {
  for (const DiagnosisItem& x : d.diagnoses) {
    const bool stream = x.code == top::Diagnosis::stream_rate ||
                        x.code == top::Diagnosis::stream_stalled ||
                        x.code == top::Diagnosis::stream_never_started;
    std::string t = x.message;
    if (x.ts != kNoTime) t += " (from " + clock_text(x.ts) + ")";
    if (x.conv) t += ", conversation " + std::to_string(x.conv);
    add(rep, x.severity == top::Severity::error ? 88 : 75, x.severity, std::move(t),
        stream ? "streams" : "code-" + std::string(top::to_string(x.code)));
    rep.facts.back().code = x.code;
    rep.facts.back().frame = x.frame;
    rep.facts.back().count = x.count;
  }
}

// Response flags, grouped by identifier.
void response_facts(Report& rep) {
  // per identifier: other way, never, range, superseded, other way with the
  // sign trait unknown; the first flagged
  struct Flags {
    std::string_view id;
    std::array<std::uint64_t, 5> n{};
    std::int64_t first = kNoTime;
  };
  std::vector<Flags> all;  // a handful of identifiers: a linear search
  for (const auto& a : rep.angles) {
    auto it =
        std::find_if(all.begin(), all.end(), [&](const Flags& f) { return f.id == a.cmd->ident; });
    if (it == all.end()) it = all.insert(all.end(), Flags{a.cmd->ident});
    auto& f = it->n;
    if (a.other_way) ++f[a.ambiguous ? 4 : 0];
    if (a.never_reached && !a.other_way && !a.no_attitude) ++f[1];
    if (a.out_of_range) ++f[2];
    if (a.superseded && !a.other_way) ++f[3];
    if ((a.other_way || a.never_reached) && it->first == kNoTime) it->first = a.cmd->t;
  }
  std::sort(all.begin(), all.end(), [](const Flags& a, const Flags& b) { return a.id < b.id; });
  std::map<std::string_view, std::array<std::uint64_t, 5>> flags;
  std::map<std::string_view, std::int64_t> first_flag;
  for (const auto& f : all) {
    flags[f.id] = f.n;
    first_flag[f.id] = f.first;
  }
  auto plural = [](std::uint64_t n, std::string_view id) {
    return std::to_string(n) + " " + std::string(id) + (n == 1 ? " command" : " commands");
  };
  for (const auto& [id, f] : flags) {
    // Each command's own flag, an observation: the verdict is the session's
    // direction-inverted, judged over the windows of an axis (a single
    // command that overshot or was superseded is no inversion).
    if (f[0])
      add(rep, 35, top::Severity::info,
          plural(f[0], id) +
              " moved the gimbal the other way of their target (see direction-inverted)",
          "response");
    if (f[4])
      add(rep, 20, top::Severity::info,
          plural(f[4], id) +
              " moved the gimbal the other way of the document's sign, as a field sign trait "
              "of the dialect has it (docs/FIELD.md): which way is right depends on the model "
              "(--model)",
          "response");
    if (f[1])
      add(rep, 70, top::Severity::warning,
          plural(f[1], id) + " never brought the gimbal within " +
              fmt("%g", rep.opts.tolerance_deg) + " deg of the target (first at " +
              clock_text(first_flag[id]) + ")",
          "response");
    if (f[2])
      add(rep, 50, top::Severity::warning,
          plural(f[2], id) + " asked for an angle outside the model's range (clamped)", "response");
    if (f[3])
      add(rep, 15, top::Severity::info, plural(f[3], id) + " superseded before the gimbal settled",
          "response");
  }
}

// Rate commands not refreshed, and the speed scale they showed.
void rate_facts(Report& rep) {
  // refresh-gap itself is the session's diagnosis (analyzer/diagnoses/
  // refresh_gap.cpp, in "What went wrong" with the rest); rep.gaps lists
  // each gap for the rates section.
  if (rep.scale_verdict != ScaleVerdict::none)
    add(rep, 25, top::Severity::info,
        "rate commands moved the gimbal at " + fmt("%.3f", rep.scale_measured) +
            " deg/s per step over " + std::to_string(rep.scale_runs) + " run" +
            (rep.scale_runs == 1 ? "" : "s") +
            (rep.scale_verdict == ScaleVerdict::field
                 ? ": the field's 0.5 deg/s, not the document's 0.1"
             : rep.scale_verdict == ScaleVerdict::document
                 ? ": the document's 0.1 deg/s, not the field's 0.5"
                 : ": neither the document's 0.1 nor the field's 0.5"),
        "rates");
}

// Frame findings: errors and warnings by code, with who sent them.
void code_facts(const ReportSink& d, Report& rep) {
  for (const auto& [code, c] : d.codes) {
    // unanswered requests and diagnoses have facts of their own
    if (c.severity == top::Severity::info ||
        (c.acode && (*c.acode == ACode::unanswered || diagnosis_of(*c.acode))))
      continue;
    std::string t = code + ": " + std::to_string(c.count) + (c.count == 1 ? " time" : " times");
    if (c.senders.size() == 1)
      t += (c.count == 1 ? ", from " : ", all from ") + c.senders.begin()->first;
    else if (!c.senders.empty())
      t += ", from " + std::to_string(c.senders.size()) + " senders";
    t += " (" + clock_text(c.first) + (c.count > 1 ? " to " + clock_text(c.last) : "") + ")";
    add(rep, c.severity == top::Severity::error ? 90 : 40, c.severity, std::move(t),
        "code-" + code);
  }
}

}  // namespace

void facts(const ReportSink& d, Report& rep) {
  unanswered_facts(d, rep);
  diagnosis_facts(d, rep);
  response_facts(rep);
  rate_facts(rep);
  code_facts(d, rep);
  std::stable_sort(rep.facts.begin(), rep.facts.end(),
                   [](const Fact& a, const Fact& b) { return a.rank > b.rank; });
}

}  // namespace topdump::report
