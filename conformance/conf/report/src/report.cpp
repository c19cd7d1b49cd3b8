#include "conf/report.hpp"

#include <cstdio>
#include <iomanip>

#include "junit.hpp"
#include "top/detail/text.hpp"

namespace topconf {

using top::markup_escape;

namespace {

std::string ms(std::uint64_t us) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", static_cast<double>(us) / 1000.0);
  return b;
}

// ANSI colours by verdict: pass green, non-strict yellow, fail red, n/a
// dim, inconclusive cyan, error magenta.
constexpr const char* kColor[] = {"\x1b[32m", "\x1b[33m", "\x1b[31m",
                                  "\x1b[2m",  "\x1b[36m", "\x1b[35m"};
static_assert(std::size(kColor) == static_cast<std::size_t>(Verdict::error) + 1);

const char* color_of(Verdict v) {
  const auto i = static_cast<std::size_t>(v);
  return i < std::size(kColor) ? kColor[i] : "\x1b[2m";
}

std::string compat_line(const drivers::Compatibility& c) {
  return std::string(c.profile->name) + " on " + std::string(top::to_string(c.model)) + ": " +
         c.text();
}

// The driver's verdict and each need: grade, feature, result, what it protects.
void write_html_compat(std::ostream& os, const drivers::Compatibility& c) {
  const char* cls = c.level == drivers::Compatibility::Level::compatible ? "pass"
                    : c.level == drivers::Compatibility::Level::without  ? "non-strict"
                                                                         : "fail";
  os << "<h2>Compatibility: " << markup_escape(c.profile->title) << "</h2>\n<p class=\"" << cls
     << "\"><b>" << markup_escape(compat_line(c)) << "</b> (exit status " << c.exit_code()
     << ")</p>\n<table><tr><th>need</th><th>grade</th><th>feature</th><th>result</th>"
        "<th>the driver's reasoning, and this device</th></tr>\n";
  for (const drivers::NeedResult& n : c.needs)
    os << "<tr class=\""
       << (n.served                                ? "pass"
           : n.need->grade == drivers::Grade::info ? "na"
                                                   : "fail")
       << "\"><td><code>" << markup_escape(n.need->id) << "</code></td><td>"
       << drivers::to_string(n.need->grade) << "</td><td>" << markup_escape(n.need->feature)
       << "</td><td>" << (n.served ? "served" : "not served") << "</td><td>"
       << markup_escape(n.outcome) << "</td></tr>\n";
  os << "</table>\n";
}

}  // namespace

std::string printable(std::string_view bytes) { return top::escape(bytes); }

void write_console(std::ostream& os, const RunResult& r, bool color,
                   const drivers::Compatibility* compat) {
  if (r.unreachable) {
    os << "topconf: target unreachable: " << r.unreachable_reason << "\n";
    if (compat) os << compat_line(*compat) << "\n";
    return;
  }
  std::size_t w = 10;
  for (const auto& c : r.cases) w = std::max(w, c.spec->id.size());
  os << std::left << std::setw(static_cast<int>(w)) << "case"
     << "  " << std::setw(6) << "level"
     << "  " << std::setw(12) << "result"
     << "  " << std::right << std::setw(8) << "ms"
     << "  reason\n";
  for (const auto& c : r.cases) {
    std::string v(to_string(c.verdict));
    if (c.flaky) v += "*";
    os << std::left << std::setw(static_cast<int>(w)) << c.spec->id << "  " << std::setw(6)
       << to_string(c.spec->level) << "  ";
    if (color) os << color_of(c.verdict);
    os << std::setw(12) << v;
    if (color) os << "\x1b[0m";
    os << "  " << std::right << std::setw(8) << ms(c.duration_us) << "  " << c.reason << "\n";
  }
  os << "\n"
     << r.cases.size() << " case(s) against " << r.target << " (" << top::to_string(r.model)
     << "): " << r.count(Verdict::pass) << " pass, " << r.count(Verdict::non_strict)
     << " non-strict, " << r.count(Verdict::fail) << " fail, " << r.count(Verdict::not_applicable)
     << " n/a, " << r.count(Verdict::inconclusive) << " inconclusive, " << r.count(Verdict::error)
     << " error";
  std::size_t flaky = 0;
  for (const auto& c : r.cases) flaky += c.flaky ? 1 : 0;
  if (flaky) os << " (" << flaky << " flaky, marked *)";
  char secs[32];
  std::snprintf(secs, sizeof secs, "%.2f", r.seconds);
  os << " in " << secs << " s\n";
  if (!r.probe_note.empty()) os << r.probe_note << "\n";
  if (compat) {
    for (const drivers::NeedResult& n : compat->needs)
      if (!n.served && n.need->grade != drivers::Grade::info)
        os << "  " << drivers::to_string(n.need->grade) << " " << n.need->id << ": " << n.outcome
           << "\n";
    os << compat_line(*compat) << "\n";
    return;
  }
  os << (r.exit_code() == 0 ? "PASS" : "FAIL") << ": every must/should case "
     << (r.exit_code() == 0 ? "passed or is not applicable" : "did not pass") << "\n";
}

nlohmann::json to_json(const RunResult& r, const drivers::Compatibility* compat) {
  nlohmann::json j;
  j["tool"] = "topconf";
  j["target"] = r.target;
  j["matrix"] = r.matrix_file;
  j["model"] = std::string(top::to_string(r.model));
  j["started_at"] = r.started_at;
  j["seconds"] = r.seconds;
  if (r.seeded) j["seed"] = r.seed;
  j["exit_code"] = r.exit_code();
  if (r.unreachable) j["unreachable"] = r.unreachable_reason;
  if (!r.probe_note.empty()) j["probe_note"] = r.probe_note;
  nlohmann::json counts;
  for (Verdict v : {Verdict::pass, Verdict::non_strict, Verdict::fail, Verdict::not_applicable,
                    Verdict::inconclusive, Verdict::error})
    counts[std::string(to_string(v))] = r.count(v);
  j["summary"] = counts;
  j["cases"] = nlohmann::json::array();
  for (const auto& c : r.cases) {
    nlohmann::json k;
    k["id"] = c.spec->id;
    k["section"] = c.spec->section;
    k["title"] = c.spec->title;
    k["level"] = std::string(to_string(c.spec->level));
    k["tags"] = c.spec->tags;
    k["result"] = std::string(to_string(c.verdict));
    k["flaky"] = c.flaky;
    k["attempts"] = c.attempts;
    k["reason"] = c.reason;
    k["started_at"] = c.started_at;
    k["start_ms"] = static_cast<double>(c.start_us) / 1000.0;
    k["duration_ms"] = static_cast<double>(c.duration_us) / 1000.0;
    nlohmann::json tr = nlohmann::json::array();
    for (const auto& e : c.transcript)
      tr.push_back({{"t_ms", static_cast<double>(e.t_us) / 1000.0},
                    {"dir", e.dir == '>'   ? "sent"
                            : e.dir == '<' ? "received"
                                           : "note"},
                    {"bytes", printable(e.bytes)}});
    k["transcript"] = tr;
    if (c.dropped_exchanges) k["transcript_dropped"] = c.dropped_exchanges;
    j["cases"].push_back(k);
  }
  if (compat) {
    j["compatibility"] = drivers::to_json(*compat);
    j["exit_code"] = compat->exit_code();
  }
  return j;
}

void write_junit(std::ostream& os, const RunResult& r, const drivers::Compatibility* compat) {
  std::size_t failures =
      r.count(Verdict::fail) + r.count(Verdict::non_strict) + r.count(Verdict::inconclusive);
  detail::JunitSuite suite;
  suite.name = "topconf." + std::string(top::to_string(r.model));
  suite.tests = r.cases.size() + (compat ? 1 : 0);
  const bool broken = compat && compat->level == drivers::Compatibility::Level::incompatible;
  suite.failures = failures + (broken ? 1 : 0);
  suite.errors = r.count(Verdict::error) + (r.unreachable ? 1 : 0);
  suite.skipped = r.count(Verdict::not_applicable);
  suite.seconds = r.seconds;
  suite.timestamp = r.started_at;
  detail::open_junit(os, suite);
  using Result = detail::JunitCase::Result;
  if (r.unreachable)
    detail::write_case(os, {.classname = "topconf",
                            .name = "liveness",
                            .result = Result::error,
                            .message = r.unreachable_reason});
  if (compat) {
    // The driver's verdict: a failure only when the driver breaks.
    detail::write_case(os, {.classname = "topconf.driver." + std::string(compat->profile->name),
                            .name = "compatibility",
                            .result = broken ? Result::failure : Result::pass,
                            .message = broken ? compat->text() : "",
                            .out = compat_line(*compat)});
  }
  for (const auto& c : r.cases) {
    detail::JunitCase k{.classname = std::string(c.spec->section),
                        .name = std::string(c.spec->id),
                        .seconds = static_cast<double>(c.duration_us) / 1e6,
                        .message = std::string(to_string(c.verdict)) + ": " + c.reason};
    switch (c.verdict) {
      case Verdict::pass:
        break;
      case Verdict::not_applicable:
        k.result = Result::skipped;
        break;
      case Verdict::error:
        k.result = Result::error;
        break;
      default:
        // may-level cases are reported but do not fail the suite.
        k.result = c.spec->level == Level::may ? Result::skipped : Result::failure;
        if (k.result == Result::failure) k.type = std::string(to_string(c.verdict));
    }
    k.out.emplace();
    for (const auto& e : c.transcript)
      *k.out += ms(e.t_us) + " " + std::string(1, e.dir) + " " + printable(e.bytes) + "\n";
    detail::write_case(os, k);
  }
  detail::close_junit(os);
}

void write_table_page_top(std::ostream& os, std::string_view title, std::string_view heading,
                          std::string_view intro_html, std::string_view corner,
                          std::string_view summary, const std::vector<TableColumnTop>& columns) {
  write_html_head(os, title);
  os << "<h1>" << markup_escape(heading) << "</h1>\n<p>" << intro_html << "</p>\n<table><tr><th>"
     << markup_escape(corner) << "</th>";
  for (const TableColumnTop& c : columns) os << "<th>" << c.head_html << "</th>";
  os << "</tr>\n<tr><th>" << markup_escape(summary) << "</th>";
  for (const TableColumnTop& c : columns)
    os << "<td class=\"" << c.summary_class << "\">" << c.summary_html << "</td>";
  os << "</tr>\n";
}

void write_html_head(std::ostream& os, std::string_view title) {
  os << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>"
     << markup_escape(title) << "</title>\n<style>\n"
     << "body{font-family:system-ui,sans-serif;margin:2em;color:#222}"
     << "table{border-collapse:collapse;width:100%}td,th{border:1px solid #ccc;padding:4px "
        "8px;text-align:left;vertical-align:top}"
     << "th{background:#f3f3f3}.pass{background:#e6f6e6}.non-strict{background:#fff5d6}.fail{"
        "background:#fbe3e3}"
     << ".error{background:#f3e0f7}.inconclusive{background:#e0f2f7}.na{color:#888}"
     << "pre{margin:0;font-size:12px;white-space:pre-wrap}details summary{cursor:pointer}"
     << ".sum span{display:inline-block;margin-right:1em;padding:2px "
        "8px;border-radius:4px}\n</style></head><body>\n";
}

void write_html(std::ostream& os, const RunResult& r, const drivers::Compatibility* compat) {
  write_html_head(os, "topconf " + std::string(top::to_string(r.model)) + " report");
  os << "<h1>topconf report: " << markup_escape(top::to_string(r.model)) << "</h1>\n";
  os << "<p>Target <b>" << markup_escape(r.target) << "</b>, matrix <code>"
     << markup_escape(r.matrix_file) << "</code>, started " << markup_escape(r.started_at) << ", "
     << r.seconds << " s";
  if (r.seeded) os << ", seed " << r.seed;
  os << ".</p>\n";
  if (r.unreachable)
    os << "<p class=\"fail\"><b>Target unreachable:</b> " << markup_escape(r.unreachable_reason)
       << "</p>\n";
  if (!r.probe_note.empty()) os << "<p>" << markup_escape(r.probe_note) << "</p>\n";
  if (compat) write_html_compat(os, *compat);
  os << "<p class=\"sum\">";
  for (Verdict v : {Verdict::pass, Verdict::non_strict, Verdict::fail, Verdict::not_applicable,
                    Verdict::inconclusive, Verdict::error}) {
    const std::string cls = v == Verdict::not_applicable ? "na" : std::string(to_string(v));
    os << "<span class=\"" << cls << "\">" << to_string(v) << ": " << r.count(v) << "</span>";
  }
  os << "</p>\n<p><b>" << (r.exit_code() == 0 ? "PASS" : "FAIL") << "</b>: exit status "
     << r.exit_code() << " (0 when every must and should case passes or is not applicable).</p>\n";
  os << "<table><tr><th>case</th><th>section</th><th>level</th><th>result</th><th>ms</"
        "th><th>reason and transcript</th></tr>\n";
  for (const auto& c : r.cases) {
    const std::string cls =
        c.verdict == Verdict::not_applicable ? "na" : std::string(to_string(c.verdict));
    os << "<tr class=\"" << cls << "\"><td><code>" << markup_escape(c.spec->id) << "</code><br>"
       << markup_escape(c.spec->title) << "</td><td>" << markup_escape(c.spec->section)
       << "</td><td>" << to_string(c.spec->level) << "</td><td>" << to_string(c.verdict)
       << (c.flaky ? " (flaky)" : "") << "</td><td>" << ms(c.duration_us) << "</td><td>"
       << markup_escape(c.reason);
    if (!c.transcript.empty()) {
      os << "<details><summary>transcript (" << c.transcript.size() << ")</summary><pre>";
      for (const auto& e : c.transcript)
        os << markup_escape(ms(e.t_us) + " ms " +
                            (e.dir == '>'   ? "sent     "
                             : e.dir == '<' ? "received "
                                            : "note     ") +
                            printable(e.bytes))
           << "\n";
      if (c.dropped_exchanges) os << "... " << c.dropped_exchanges << " more not kept\n";
      os << "</pre></details>";
    }
    os << "</td></tr>\n";
  }
  os << "</table>\n</body></html>\n";
}

}  // namespace topconf
