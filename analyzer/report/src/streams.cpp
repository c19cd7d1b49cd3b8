// topdump report: each stream's rate over time and its gaps.
#include <algorithm>
#include <cstdio>

#include "diagnoses/stream_stalled.hpp"
#include "report/analysis.hpp"
#include "report/report.hpp"

namespace topdump::report {

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

void streams(const ReportSink& d, const Stats& st, Report& rep) {
  for (const ConvStats& cs : st.conversations) {
    for (const StreamStat& ss : cs.streams) {
      StreamResult r;
      r.conv = cs.id;
      r.stat = ss;
      auto c = d.convs.find(cs.id);
      const std::vector<std::int64_t>* t = nullptr;
      if (c != d.convs.end()) {
        auto a = c->second.attitude.find(ss.ident);
        if (a != c->second.attitude.end()) t = &a->second.push_t;
      }
      if (t && t->size() >= 2) {
        const std::int64_t span = t->back() - t->front();
        r.bucket_us =
            std::max<std::int64_t>(1'000'000, (span / 300 + 999'999) / 1'000'000 * 1'000'000);
        r.rate.assign(static_cast<std::size_t>(span / r.bucket_us + 1), 0.f);
        for (std::int64_t x : *t)
          r.rate[static_cast<std::size_t>((x - t->front()) / r.bucket_us)] += 1.f;
        for (auto& v : r.rate) v /= static_cast<float>(r.bucket_us) / 1e6f;
        // the last bucket is partial
        const std::int64_t last_len = span % r.bucket_us;
        if (last_len > 0)
          r.rate.back() *= static_cast<float>(r.bucket_us) / static_cast<float>(last_len);
        else
          r.rate.pop_back();
        const double hz = ss.asked_hz > 0 ? ss.asked_hz : ss.measured_hz();
        const double period_us = hz > 0 ? 1e6 / hz : 1e6;
        for (std::size_t i = 1; i < t->size(); ++i) {
          const double dt = static_cast<double>((*t)[i] - (*t)[i - 1]);
          if (diag::stream_gap(dt, period_us)) {
            ++r.gap_count;
            r.gaps.push_back({(*t)[i - 1], dt / 1000.0});
          }
        }
        std::sort(r.gaps.begin(), r.gaps.end(),
                  [](const auto& a, const auto& b) { return a.ms > b.ms; });
        if (r.gaps.size() > 10) r.gaps.resize(10);
      }
      rep.streams.push_back(std::move(r));
    }
  }
}

}  // namespace topdump::report
