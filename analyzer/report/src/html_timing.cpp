// topdump report, the HTML page: latency and streams.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "capture/sources.hpp"
#include "diagnoses/stream_stalled.hpp"
#include "html_page.hpp"
#include "report/report.hpp"
#include "svg.hpp"
#include "top/detail/text.hpp"

namespace topdump::report::html {

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
       "<th>frames</th><th>gaps over " +
       std::to_string(diag::kGapPeriods) + " periods</th></tr>";
  for (const auto& x : r.streams)
    o += "<tr>" + tdn(std::to_string(x.conv)) + td(x.stat.ident) + td(x.stat.asked_by) +
         tdn(!x.stat.periodic      ? std::string("event push (no rate)")
             : x.stat.asked_hz > 0 ? fmt("%g Hz", x.stat.asked_hz)
                                   : std::string("on (device rate)")) +
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

}  // namespace topdump::report::html
