// topdump report: the HTML page. One self-contained, well-formed
// (XHTML-compatible) HTML5 file: inline CSS, inline SVG plots, no script,
// no external URL. Sections are described in docs/REPORT.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "capture/sources.hpp"
#include "report/report.hpp"
#include "svg.hpp"
#include "top/text.hpp"

namespace topdump::report {

namespace {

using top::markup_escape;

constexpr std::size_t kMaxRows = 300;  // table rows per table (the JSON has all)
constexpr int kWidth = 960;
const char* const kAxisColor[kAxes] = {"#1f77b4", "#d62728", "#2ca02c"};
const char* const kCmdColor[kAxes] = {"#0b3c66", "#7a1010", "#145214"};

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

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string sev_span(top::Severity s) {
  const std::string n(top::to_string(s));
  return "<span class=\"sev-" + n + "\">" + n + "</span>";
}

std::string td(const std::string& s) { return "<td>" + s + "</td>"; }
std::string tdn(const std::string& s) { return "<td class=\"n\">" + s + "</td>"; }
std::string frame_ref(std::uint64_t n) { return n ? "#" + std::to_string(n) : "-"; }

std::string more_rows(std::size_t total) {
  return total > kMaxRows ? "<p class=\"muted\">" + std::to_string(total - kMaxRows) +
                                " more rows in <code>topdump report --json</code>.</p>"
                          : "";
}

struct Page {
  const Report& r;
  std::string& o;
  std::int64_t t0 = 0, t1 = 0;  // the time axis of every plot

  void overview();
  void motion();
  void response();
  void latency();
  void streams();
  void findings();
  void unanswered();

  // Opens section `id` under heading `title`. With nothing to show
  // (`empty`), writes `none` (a muted or ok paragraph), closes the section
  // and returns false.
  bool open(std::string_view id, std::string_view title, bool empty, std::string_view none) {
    o += "<section id=\"";
    o += id;
    o += "\"><h2>";
    o += title;
    o += "</h2>";
    if (!empty) return true;
    o += none;
    o += "</section>";
    return false;
  }
};

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
  o += "<tr><th>pairing</th><td>" + std::to_string(s.requests) + " requests, " +
       std::to_string(s.responses) + " responses, " + std::to_string(s.paired) + " paired, " +
       std::to_string(s.unanswered) + " unanswered, " + std::to_string(s.unsolicited) +
       " unsolicited</td></tr>";
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
      o += "<li>" + sev_span(f.severity) + " " + markup_escape(f.text) + " <a href=\"#" +
           markup_escape(f.anchor) + "\">details</a></li>";
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

void Page::motion() {
  o += "<section id=\"motion\"><h2>2. Gimbal motion</h2>";
  o += "<p class=\"muted\">Per conversation and axis: the reported attitude (GAC/GIC replies and "
       "pushes, solid), the commanded angle (dashed, held until the next command), angle "
       "commands (diamonds at their target), rate commands (triangles above the plot: up "
       "positive, down negative, circle zero) and other gimbal commands (dotted lines). Hover a "
       "mark for its frame.</p>";
  bool any = false;
  for (const auto& [id, c] : r.data->convs) {
    if (c.attitude.empty() && c.angles.empty() && c.rates.empty() && c.marks.empty()) continue;
    any = true;
    o += "<h3>Conversation " + std::to_string(id) + ": <code>" + markup_escape(c.a) +
         "</code> and <code>" + markup_escape(c.b) + "</code> (" +
         markup_escape(std::string(top::to_string(c.dialect))) + ")</h3>";
    for (int axis = 0; axis < kAxes; ++axis) {
      svg::TimePlot p;
      p.width = kWidth;
      p.height = 210;
      p.t0 = t0;
      p.t1 = t1;
      p.title = std::string(axis_name(axis));
      p.unit = "deg";
      bool has_motion = false;
      for (const auto& [ident, a] : c.attitude) {
        svg::Series s;
        s.label = ident + " " + axis_name(axis);
        s.color = ident == "GIC" ? "#9467bd" : kAxisColor[axis];
        s.t = a.t;
        s.v = a.v[static_cast<std::size_t>(axis)];
        s.break_us = 2'000'000;
        const auto mm = std::minmax_element(s.v.begin(), s.v.end());
        if (mm.first != s.v.end() && *mm.second - *mm.first > 0.005f) has_motion = true;
        p.series.push_back(std::move(s));
      }
      svg::Series cmd;
      cmd.label = "commanded";
      cmd.color = kCmdColor[axis];
      cmd.step = true;
      cmd.dashed = true;
      // One mark per three pixel columns and shape: the first, with a count
      // (the title of each is only built for the ones drawn).
      // (commands come in time order: the last column of each shape is enough)
      std::map<char, std::pair<long, std::size_t>> last;
      auto mark = [&](std::int64_t t, char shape, auto make) {
        const long col = svg::column(p, t) / 3;  // a mark is about 8 px wide
        auto [it, fresh] = last.try_emplace(shape, col, p.markers.size());
        if (!fresh && it->second.first == col) {
          ++p.markers[it->second.second].count;
          return;
        }
        it->second = {col, p.markers.size()};
        p.markers.push_back(make());
      };
      for (const auto& a : c.angles) {
        if (a.axis != axis) continue;
        cmd.t.push_back(a.t);
        cmd.v.push_back(static_cast<float>(a.target));
        mark(a.t, 'd', [&] {
          return svg::Marker{a.t,
                             a.target,
                             false,
                             'd',
                             kCmdColor[axis],
                             std::string(a.ident) + " " + fmt("%.2f", a.target) + " deg, speed " +
                                 fmt("%.1f", a.speed) + " deg/s (frame " + std::to_string(a.frame) +
                                 ", " + clock_text(a.t) + ")"};
        });
      }
      for (const auto& x : c.rates) {
        if (x.axis != axis) continue;
        const char shape = x.steps > 0 ? '^' : x.steps < 0 ? 'v' : 'o';
        mark(x.t, shape, [&] {
          return svg::Marker{x.t,
                             0,
                             true,
                             shape,
                             kCmdColor[axis],
                             std::string(x.ident) + " " + std::to_string(x.steps) + " steps (" +
                                 fmt("%.1f", x.rate) + " deg/s by the catalog, frame " +
                                 std::to_string(x.frame) + ", " + clock_text(x.t) + ")"};
        });
      }
      for (const auto& m : c.marks)
        mark(m.t, '|', [&] {
          return svg::Marker{m.t,
                             0,
                             false,
                             '|',
                             "#777",
                             std::string(m.ident) + " " + std::string(m.what) + " (frame " +
                                 std::to_string(m.frame) + ", " + clock_text(m.t) + ")"};
        });
      const bool has_cmd =
          !cmd.t.empty() || std::any_of(c.rates.begin(), c.rates.end(),
                                        [&](const RateCommand& x) { return x.axis == axis; });
      if (!has_cmd && !has_motion && axis != 0) continue;  // yaw always: even a still gimbal
      if (!cmd.t.empty()) p.series.push_back(std::move(cmd));
      svg::time_plot(o, p);
    }
  }
  if (!any) o += "<p class=\"muted\">No gimbal command and no attitude in the capture.</p>";
  o += "</section>";
}

void Page::response() {
  o += "<section id=\"response\"><h2>3. Response analysis</h2>";
  o += "<p>Angle commands: settling time is when the attitude came within " +
       fmt("%g", r.opts.tolerance_deg) +
       " deg of the target (clamped to the model's range) and stayed there until the next "
       "command on the axis (<code>--tolerance</code>); expected is the step over the "
       "commanded speed.</p>";
  if (r.angles.empty()) {
    o += "<p class=\"muted\">No angle command.</p>";
  } else {
    o += "<table><tr><th>frame</th><th>time</th><th>conv</th><th>command</th><th>axis</th>"
         "<th>target</th><th>from</th><th>speed</th><th>expected</th><th>settling</th>"
         "<th>overshoot</th><th>steady-state error</th><th>flags</th></tr>";
    for (std::size_t i = 0; i < r.angles.size() && i < kMaxRows; ++i) {
      const AngleResult& a = r.angles[i];
      std::string flags;
      auto flag = [&](bool on, const std::string& t, bool info = false) {
        if (on)
          flags += "<span class=\"flag" + std::string(info ? " info" : "") + "\">" + t + "</span>";
      };
      flag(a.no_attitude, "no attitude", true);
      flag(a.never_reached, "never reached");
      flag(a.other_way, "moved the other way (sign inverted" +
                            (a.mirrored_settling_s >= 0
                                 ? ", at -target after " + fmt("%.3f", a.mirrored_settling_s) + " s"
                                 : std::string()) +
                            ")");
      flag(a.out_of_range, "outside the range " + fmt("%g", a.cmd->min) + ".." +
                               fmt("%g", a.cmd->max) + ": clamped");
      flag(a.superseded, "superseded", true);
      o += "<tr>" + tdn(frame_ref(a.cmd->frame)) + td(clock_text(a.cmd->t)) +
           tdn(std::to_string(a.conv)) + td(std::string(a.cmd->ident)) +
           td(axis_name(a.cmd->axis)) + tdn(fmt("%.2f", a.cmd->target)) +
           tdn(a.no_attitude ? "-" : fmt("%.2f", a.start)) +
           tdn(a.cmd->speed > 0 ? fmt("%.1f", a.cmd->speed) : "-") +
           tdn(a.expected_s >= 0 ? fmt("%.3f s", a.expected_s) : "-") +
           tdn(a.settling_s >= 0 ? fmt("%.3f s", a.settling_s) : "-") +
           tdn(a.no_attitude ? "-" : fmt("%.2f deg", a.overshoot_deg)) +
           tdn(a.no_attitude ? "-" : fmt("%.2f deg", a.final_error)) + td(flags) + "</tr>";
    }
    o += "</table>" + more_rows(r.angles.size());
  }
  o += "<h3 id=\"rates\">Rate commands</h3>";
  if (r.runs.empty()) {
    o += "<p class=\"muted\">No rate command.</p>";
  } else {
    o += "<p>Runs of rate commands (one axis, one value, each refreshed within the limit). "
         "Measured rate: least squares over the attitude during the run.";
    if (r.refresh_limit_ms)
      o += " Refresh limit " + std::to_string(r.refresh_limit_ms) +
           " ms (field: " + markup_escape(r.refresh_evidence) + ").";
    o += "</p>";
    if (!r.scale_verdict.empty()) {
      o += "<p><b>Speed unit:</b> the gimbal moved " + fmt("%.3f", r.scale_measured) +
           " deg/s per step (median of " + std::to_string(r.scale_runs) + " run" +
           (r.scale_runs == 1 ? "" : "s") + "). ";
      o += r.scale_verdict == "0.5"   ? "The capture supports the field's 0.5 deg/s per step, "
                                        "not the document's 0.1."
           : r.scale_verdict == "0.1" ? "The capture supports the document's 0.1 deg/s per "
                                        "step, not the field's 0.5."
                                      : "The capture supports neither 0.1 (document) nor 0.5 "
                                        "(field) deg/s per step.";
      o += "</p>";
    }
    o += "<table><tr><th>frame</th><th>start</th><th>conv</th><th>command</th><th>axis</th>"
         "<th>commands</th><th>steps</th><th>commanded</th><th>refresh median / max</th>"
         "<th>measured</th><th>per step</th></tr>";
    for (std::size_t i = 0; i < r.runs.size() && i < kMaxRows; ++i) {
      const RateRun& x = r.runs[i];
      o += "<tr>" + tdn(frame_ref(x.first_frame)) + td(clock_text(x.start)) +
           tdn(std::to_string(x.conv)) + td(x.ident) + td(axis_name(x.axis)) +
           tdn(std::to_string(x.commands)) + tdn(std::to_string(x.steps)) +
           tdn(fmt("%.1f deg/s", x.commanded)) +
           tdn(x.commands > 1
                   ? fmt("%.0f", x.median_interval_ms) + " / " + fmt("%.0f ms", x.max_interval_ms)
                   : "-") +
           tdn(x.measured_ok ? fmt("%.2f deg/s", x.measured) : "-") +
           tdn(x.measured_ok ? fmt("%.3f", x.per_step) : "-") + "</tr>";
    }
    o += "</table>" + more_rows(r.runs.size());
    if (!r.gaps.empty()) {
      o += "<h3>Refresh gaps</h3><p>Rate commands not followed by another on the axis within " +
           std::to_string(r.refresh_limit_ms) +
           " ms: the motors stop.</p><table><tr><th>frame"
           "</th><th>time</th><th>conv</th><th>command</th><th>gap</th></tr>";
      for (std::size_t i = 0; i < r.gaps.size() && i < kMaxRows; ++i) {
        const RefreshGap& g = r.gaps[i];
        o += "<tr>" + tdn(frame_ref(g.frame)) + td(clock_text(g.t)) + tdn(std::to_string(g.conv)) +
             td(g.ident) + tdn(fmt("%.0f ms", g.gap_ms)) + "</tr>";
      }
      o += "</table>" + more_rows(r.gaps.size());
    }
  }
  o += "</section>";
}

void Page::latency() {
  const Stats& s = *r.stats;
  if (!open("latency", "4. Latency", s.latency.empty(),
            "<p class=\"muted\">No request was answered.</p>"))
    return;
  o += "<table><tr><th>identifier</th><th>pairs</th><th>min</th><th>median</th><th>p90</th>"
       "<th>p95</th><th>p99</th><th>max</th></tr>";
  auto ms = [](std::int64_t us) { return fmt("%.3f ms", static_cast<double>(us) / 1000.0); };
  for (const auto& [k, l] : s.latency)
    o += "<tr>" + td(markup_escape(k)) + tdn(std::to_string(l.count())) + tdn(ms(l.min())) +
         tdn(ms(l.quantile(0.5))) + tdn(ms(l.quantile(0.9))) + tdn(ms(l.quantile(0.95))) +
         tdn(ms(l.quantile(0.99))) + tdn(ms(l.max())) + "</tr>";
  o += "</table><h3>Histograms (ms, five bins per decade)</h3>";
  for (const auto& [k, bins] : r.data->latency_bins) {
    std::size_t lo = kLatencyBins, hi = 0;
    for (std::size_t b = 0; b < kLatencyBins; ++b)
      if (bins[b]) lo = std::min(lo, b), hi = b;
    if (lo > hi) continue;
    std::vector<std::string> labels;
    std::vector<std::uint64_t> counts;
    for (std::size_t b = lo; b <= hi; ++b) {
      const double v = latency_bin_ms(b);
      labels.push_back(v < 1 ? fmt("%.2g", v) : fmt("%.0f", v));
      counts.push_back(bins[b]);
    }
    o += "<div class=\"hist\"><b>" + markup_escape(k) + "</b>";
    svg::bars(o, labels, counts, "#4c78a8",
              std::min(kWidth, 40 + 36 * static_cast<int>(counts.size())), 90);
    o += "</div>";
  }
  std::vector<Slow> slow = r.data->slowest;
  std::sort(slow.begin(), slow.end(),
            [](const Slow& a, const Slow& b) { return a.latency_us > b.latency_us; });
  o += "<h3>Slowest exchanges</h3><table><tr><th>latency</th><th>identifier</th><th>request"
       "</th><th>response</th><th>time</th><th>conv</th><th>response bytes</th></tr>";
  for (const Slow& x : slow)
    o += "<tr>" + tdn(ms(x.latency_us)) + td(markup_escape(x.ident)) + tdn(frame_ref(x.request)) +
         tdn(frame_ref(x.response)) + td(clock_text(x.ts)) + tdn(std::to_string(x.conv)) +
         td("<span class=\"raw\">" + markup_escape(top::escape(x.response_raw)) + "</span>") +
         "</tr>";
  o += "</table></section>";
}

void Page::streams() {
  if (!open("streams", "5. Streams", r.streams.empty(),
            "<p class=\"muted\">No push stream was switched on.</p>"))
    return;
  o += "<table><tr><th>conv</th><th>stream</th><th>asked by</th><th>asked</th><th>measured</th>"
       "<th>frames</th><th>gaps over 3 periods</th></tr>";
  for (const auto& x : r.streams)
    o += "<tr>" + tdn(std::to_string(x.conv)) + td(x.stat.ident) + td(x.stat.asked_by) +
         tdn(x.stat.asked_hz > 0 ? fmt("%g Hz", x.stat.asked_hz) : "on (device rate)") +
         tdn(fmt("%.2f Hz", x.stat.measured_hz())) + tdn(std::to_string(x.stat.frames)) +
         tdn(std::to_string(x.gap_count)) + "</tr>";
  o += "</table>";
  for (const auto& x : r.streams) {
    if (x.rate.empty()) continue;
    svg::TimePlot p;
    p.width = kWidth;
    p.height = 170;
    p.t0 = t0;
    p.t1 = t1;
    p.title = x.stat.ident + " rate, conversation " + std::to_string(x.conv) + ", per " +
              fmt("%g", static_cast<double>(x.bucket_us) / 1e6) + " s";
    p.unit = "Hz";
    svg::Series s;
    s.label = "measured";
    s.color = "#1f77b4";
    s.step = true;
    for (std::size_t i = 0; i < x.rate.size(); ++i) {
      s.t.push_back(x.stat.first + static_cast<std::int64_t>(i) * x.bucket_us);
      s.v.push_back(x.rate[i]);
    }
    p.series.push_back(std::move(s));
    if (x.stat.asked_hz > 0)
      p.hlines.push_back({x.stat.asked_hz, "asked " + fmt("%g", x.stat.asked_hz) + " Hz"});
    for (const auto& g : x.gaps)
      p.markers.push_back({g.t, 0, true, 'v', "#d62728",
                           "gap of " + fmt("%.0f", g.ms) + " ms at " + clock_text(g.t)});
    svg::time_plot(o, p);
    if (!x.gaps.empty()) {
      o += "<p>Longest gaps:";
      for (const auto& g : x.gaps) o += " " + fmt("%.0f ms", g.ms) + " at " + clock_text(g.t) + ";";
      o += "</p>";
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

}  // namespace

void write_html(std::string& o, const Report& r) {
  Page p{r, o};
  p.t0 = r.stats->first == kNoTime ? 0 : r.stats->first;
  p.t1 = r.stats->last == kNoTime ? 1 : r.stats->last;
  if (p.t1 <= p.t0) p.t1 = p.t0 + 1'000'000;
  o += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"/>"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>"
       "<title>topdump report</title><style>";
  o += kCss;
  o += "</style></head><body><header><h1>topdump report</h1><p>";
  for (std::size_t i = 0; i < r.opts.files.size(); ++i)
    o += (i ? ", " : "") + markup_escape(r.opts.files[i]);
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
