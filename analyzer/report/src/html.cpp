// topdump report: the HTML page. One self-contained, well-formed
// (XHTML-compatible) HTML5 file: inline CSS, inline SVG plots, no script,
// no external URL. Sections are described in docs/REPORT.md; this file
// writes the page, the overview, the findings and the unanswered requests.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "capture/sources.hpp"
#include "html_page.hpp"
#include "output/output.hpp"
#include "report/report.hpp"
#include "svg.hpp"
#include "top/detail/text.hpp"

namespace topdump::report {

namespace html {

namespace {

const char* const kCss = R"(
body{font-family:-apple-system,"Segoe UI",Roboto,"DejaVu Sans",Arial,sans-serif;margin:0;
color:#1d2329;background:#f4f6f8;font-size:14px;line-height:1.45}
header{background:#1d3557;color:#fff;padding:14px 28px}
header h1{margin:0;font-size:22px}
header p{margin:4px 0 0;color:#cfd8e3}
nav{background:#fff;border-bottom:1px solid #d6dbe1;padding:6px 28px;position:sticky;top:0}
nav a{margin-right:16px;color:#1d3557;text-decoration:none;font-weight:600}
main{padding:8px 28px 40px;max-width:1200px}
section{background:#fff;border:1px solid #d6dbe1;border-radius:6px;padding:8px 18px 14px;
margin:16px 0}
h2{font-size:18px;margin:8px 0;color:#1d3557}
h3{font-size:15px;margin:14px 0 6px}
table{border-collapse:collapse;margin:6px 0;font-size:13px}
th,td{border-bottom:1px solid #e3e7eb;padding:3px 8px;text-align:left;vertical-align:top}
th{background:#eef1f4}
td.n{text-align:right;font-variant-numeric:tabular-nums}
code,.raw{font-family:"DejaVu Sans Mono",Menlo,Consolas,monospace;font-size:12px}
.raw{word-break:break-all}
.sev-error{color:#b00020;font-weight:700}
.sev-warning{color:#b35c00;font-weight:600}
.sev-info{color:#45617a}
ol.facts li{margin:3px 0}
ol.facts .why{font-size:90%;color:#555;margin:2px 0 6px 1em}
.flag{display:inline-block;padding:0 6px;border-radius:8px;font-size:12px;margin-right:3px;
background:#fde2e1;color:#8a1111}
.flag.info{background:#e5edf5;color:#2d4a66}
.ok{color:#1b6e20}
.muted{color:#6b7785}
svg.plot{display:block;margin:6px 0;background:#fff}
svg .plotbg{fill:#fbfcfd;stroke:#c9d0d7}
svg .grid{stroke:#e6e9ec;stroke-width:1}
svg .ref{stroke:#888;stroke-width:1.2;stroke-dasharray:6,4}
svg .tick{font-size:11px;fill:#4a5561}
svg .ptitle{font-size:12px;font-weight:600;fill:#1d2329}
details{margin:4px 0}
.hist{display:inline-block;vertical-align:top;margin:0 18px 8px 0}
summary{cursor:pointer}
)";

}  // namespace

void Page::overview() {
  const Stats& s = *r.stats;
  o += "<section id=\"overview\"><h2>1. Overview</h2><table>";
  o += "<tr><th>captures</th><td>";
  for (std::size_t i = 0; i < r.opts.files.size(); ++i)
    o += (i ? "<br/>" : "") + ("<code>" + markup_escape(r.opts.files[i]) + "</code>");
  o += "</td></tr><tr><th>time span</th><td>" +
       (s.first == kNoTime
            ? std::string("no time stamps")
            : markup_escape(format_time(s.first)) + " to " + markup_escape(format_time(s.last)) +
                  " (" + fmt("%.3f", static_cast<double>(s.last - s.first) / 1e6) + " s)") +
       "</td></tr>";
  o += "<tr><th>frames</th><td>" + std::to_string(s.frames) + " (" +
       std::to_string(s.bad_checksum) + " with a bad checksum, " + std::to_string(s.error_frames) +
       " with an error), " + std::to_string(s.garbage) + " garbage runs, " +
       std::to_string(s.records) + " records</td></tr>";
  o += "<tr><th>pairing</th><td>";
  for (const StatsCount& c : kPairingCounts)
    o += std::string(&c == kPairingCounts ? "" : ", ") + std::to_string(s.*c.count) + " " +
         std::string(c.name);
  o += "</td></tr>";
  o += "<tr><th>model</th><td>" +
       (r.model == top::Model::unknown ? std::string("not given (--model): checks of every model")
                                       : std::string(top::to_string(r.model))) +
       "</td></tr>";
  o += "<tr><th>worst finding</th><td>" + sev_span(r.worst) + "</td></tr></table>";
  o += "<h3>Conversations</h3><table><tr><th>id</th><th>transport</th><th>first sender</th>"
       "<th>peer</th><th>dialect</th><th>model</th><th>frames</th><th>requests</th><th>responses</"
       "th>"
       "<th>paired</th></tr>";
  for (const ConvStats& c : s.conversations)
    o += "<tr>" + tdn(std::to_string(c.id)) + td(std::string(to_string(c.transport))) +
         td("<code>" + markup_escape(c.a) + "</code>") +
         td("<code>" + markup_escape(c.b) + "</code>") +
         td(std::string(top::to_string(dialect_of(r, c)))) +
         td(markup_escape(model_text(r, c).empty() ? "-" : model_text(r, c))) +
         tdn(std::to_string(c.frames)) + tdn(std::to_string(c.requests)) +
         tdn(std::to_string(c.responses)) + tdn(std::to_string(c.paired)) + "</tr>";
  o += "</table>";
  if (s.conversations_dropped)
    o += "<p class=\"muted\">" + std::to_string(s.conversations_dropped) +
         " more conversations not listed.</p>";
  o += "<h3 id=\"wrong\">What went wrong</h3>";
  if (r.facts.empty()) {
    o += "<p class=\"ok\">Nothing: every request was answered, every stream ran at its rate, "
         "and no frame has an error or a warning.</p>";
  } else {
    // the first twelve at once, the rest a click away
    auto item = [&](const Fact& f) {
      o += "<li>" + sev_span(f.severity) + " ";
      if (f.code) o += "<code>" + std::string(top::to_string(*f.code)) + "</code> ";
      o += markup_escape(f.text) + " <a href=\"#" + markup_escape(f.anchor) + "\">details</a>";
      if (f.code) {
        o += "<div class=\"why\"><b>Evidence:</b> " +
             markup_escape(std::string(top::evidence(*f.code))) + "<br/><b>Remedy:</b> " +
             markup_escape(std::string(top::remedy(*f.code)));
        if (f.frame) o += " (first frame " + frame_ref(f.frame) + ")";
        o += "</div>";
      }
      o += "</li>";
    };
    constexpr std::size_t kShown = 12;
    o += "<ol class=\"facts\">";
    for (std::size_t i = 0; i < r.facts.size() && i < kShown; ++i) item(r.facts[i]);
    o += "</ol>";
    if (r.facts.size() > kShown) {
      o += "<details><summary>" + std::to_string(r.facts.size() - kShown) +
           " more</summary><ol class=\"facts\" start=\"" + std::to_string(kShown + 1) + "\">";
      for (std::size_t i = kShown; i < r.facts.size(); ++i) item(r.facts[i]);
      o += "</ol></details>";
    }
  }
  o += "</section>";
}

void Page::findings() {
  const ReportSink& d = *r.data;
  if (!open("findings", "6. Findings", d.codes.empty(), "<p class=\"ok\">No finding.</p>")) return;
  std::vector<svg::Lane> ls;
  const char* names[3] = {"info", "warning", "error"};
  const char* colors[3] = {"#6b8fb3", "#e08a00", "#c8102e"};
  for (int i = 2; i >= 0; --i)
    ls.push_back({names[i], colors[i], &d.finding_times[static_cast<std::size_t>(i)]});
  if (t1 > t0) svg::lanes(o, ls, t0, t1, kWidth);
  std::vector<const CodeStat*> sorted;
  for (const auto& [k, c] : d.codes) sorted.push_back(&c);
  std::stable_sort(sorted.begin(), sorted.end(), [](const CodeStat* a, const CodeStat* b) {
    return a->severity != b->severity ? a->severity > b->severity : a->count > b->count;
  });
  o += "<table><tr><th>code</th><th>severity</th><th>count</th><th>first</th><th>last</th>"
       "<th>senders</th></tr>";
  for (const CodeStat* c : sorted) {
    std::string who;
    for (const auto& [w, n] : c->senders)
      who += (who.empty() ? "" : ", ") +
             ("<code>" + markup_escape(w) + "</code> " + std::to_string(n));
    o += "<tr>" +
         td("<a href=\"#code-" + markup_escape(c->code) + "\">" + markup_escape(c->code) + "</a>") +
         td(sev_span(c->severity)) + tdn(std::to_string(c->count)) + td(clock_text(c->first)) +
         td(clock_text(c->last)) + td(who) + "</tr>";
  }
  o += "</table><h3>Examples</h3>";
  for (const CodeStat* c : sorted) {
    o += "<details id=\"code-" + markup_escape(c->code) + "\"" +
         (c->severity == top::Severity::info ? "" : " open=\"open\"") + "><summary>" +
         sev_span(c->severity) + " <b>" + markup_escape(c->code) + "</b> (" +
         std::to_string(c->count) +
         ")</summary><table><tr><th>frame</th><th>where</th><th>time</th><th>bytes</th>"
         "<th>decoded</th><th>finding</th></tr>";
    for (const Example& x : c->examples)
      o += "<tr>" + tdn(frame_ref(x.frame)) +
           td("<code>" + markup_escape(x.file) + "</code> record " + std::to_string(x.record) +
              " @" + std::to_string(x.offset) + (x.at ? ", byte " + std::to_string(x.at) : "") +
              (x.from.empty() ? ""
                              : "<br/><code>" + markup_escape(x.from) + "</code> to <code>" +
                                    markup_escape(x.to) + "</code>")) +
           td(clock_text(x.ts)) +
           td("<span class=\"raw\">" + markup_escape(top::escape(x.raw)) + "</span>") +
           td(markup_escape(top::ascii_text(x.decoded))) +
           td(markup_escape(top::ascii_text(x.message))) + "</tr>";
    o += "</table></details>";
  }
  o += "</section>";
}

void Page::unanswered() {
  const auto& u = r.data->unanswered;
  if (!open("unanswered", "7. Unanswered requests", u.empty(),
            "<p class=\"ok\">Every request was answered.</p>"))
    return;
  o += "<p>As <code>topdump read</code> reports them, with their causes.</p><table><tr><th>"
       "frame</th><th>time</th><th>conv</th><th>file</th><th>finding</th></tr>";
  for (std::size_t i = 0; i < u.size() && i < kMaxRows; ++i)
    o += "<tr>" + tdn(frame_ref(u[i].frame)) + td(clock_text(u[i].ts)) +
         tdn(std::to_string(u[i].conv)) + td("<code>" + markup_escape(u[i].file) + "</code>") +
         td(markup_escape(top::ascii_text(u[i].message))) + "</tr>";
  o += "</table>" + more_rows(u.size()) + "</section>";
}

}  // namespace html

void write_html(std::string& o, const Report& r) {
  html::Page p{r, o};
  p.t0 = r.stats->first == kNoTime ? 0 : r.stats->first;
  p.t1 = r.stats->last == kNoTime ? 1 : r.stats->last;
  if (p.t1 <= p.t0) p.t1 = p.t0 + 1'000'000;
  o += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"/>"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>"
       "<title>topdump report</title><style>";
  o += html::kCss;
  o += "</style></head><body><header><h1>topdump report</h1><p>";
  for (std::size_t i = 0; i < r.opts.files.size(); ++i)
    o += (i ? ", " : "") + top::markup_escape(r.opts.files[i]);
  o += " - " + std::to_string(r.stats->frames) + " frames, worst finding " +
       std::string(top::to_string(r.worst)) + "</p></header>";
  o += "<nav><a href=\"#overview\">Overview</a><a href=\"#motion\">Motion</a>"
       "<a href=\"#response\">Response</a><a href=\"#latency\">Latency</a>"
       "<a href=\"#streams\">Streams</a><a href=\"#findings\">Findings</a>"
       "<a href=\"#unanswered\">Unanswered</a></nav><main>";
  p.overview();
  p.motion();
  p.response();
  p.latency();
  p.streams();
  p.findings();
  p.unanswered();
  o += "</main></body></html>\n";
}

}  // namespace topdump::report
