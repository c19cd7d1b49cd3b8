// topdump report: the analysis of the sink's data (analyze()), and the
// model as the report names it.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "report/analysis.hpp"
#include "report/report.hpp"

namespace topdump::report {

std::string_view to_string(ScaleVerdict v) noexcept {
  switch (v) {
    case ScaleVerdict::field:
      return "0.5";
    case ScaleVerdict::document:
      return "0.1";
    case ScaleVerdict::neither:
      return "neither";
    case ScaleVerdict::none:
      break;
  }
  return "";
}

top::Dialect dialect_of(const Report& r, const ConvStats& c) {
  if (c.dialect != top::Dialect::unknown) return c.dialect;
  auto it = r.data->convs.find(c.id);
  return it == r.data->convs.end() ? c.dialect : it->second.dialect;
}

std::string model_text(top::Model given, top::Dialect d, const ConvData* c) {
  if (given != top::Model::unknown) return std::string(top::to_string(given)) + " (given)";
  if (c && c->named != top::Model::unknown)
    return std::string(top::to_string(c->named)) + " (named by the device's model-name reply)";
  std::vector<top::Model> of, left;
  for (top::Model m : top::all_models())
    if (top::dialect_of(m) == d) {
      of.push_back(m);
      if (c && (c->models & top::model_bit(m))) left.push_back(m);
    }
  if (of.size() == 1)
    return std::string(top::to_string(of[0])) + " (guessed: the only model of the dialect)";
  std::string t;
  if (!left.empty() && left.size() < of.size()) {
    for (std::size_t i = 0; i < left.size(); ++i)
      t += (i == 0                 ? ""
            : i + 1 == left.size() ? " or "
                                   : ", ") +
           std::string(top::to_string(left[i]));
    t += " (guessed: the device sent " + std::string(c->narrowed_by) +
         (left.size() == 1 ? ", which the documents give to this model only)"
                           : ", which the documents give to these models only)");
  }
  if (c && !c->conflict.empty())
    t += std::string(t.empty() ? "" : "; ") + "the device sent " + std::string(c->conflict) +
         ", which the documents give to none of these";
  return t;
}

std::string model_text(const Report& r, const ConvStats& c) {
  const auto it = r.data->convs.find(c.id);
  return model_text(r.model, dialect_of(r, c), it == r.data->convs.end() ? nullptr : &it->second);
}

Report analyze(const ReportSink& data, const Stats& stats, top::Severity worst, top::Model model,
               const Options& opts) {
  Report rep;
  rep.opts = opts;
  rep.data = &data;
  rep.stats = &stats;
  rep.worst = worst;
  rep.model = model;
  std::size_t n = 0;
  for (const auto& [id, c] : data.convs) n += c.angles.size();
  rep.angles.reserve(n);
  for (const auto& [id, c] : data.convs) {
    const AxisTimes times = axis_times(c);
    for (const auto& a : c.angles)
      rep.angles.push_back(angle_result(c, times, a, model, opts.tolerance_deg));
    if (!c.rates.empty()) rate_runs(c, times, rep, stats.last);
  }
  // The speed unit from the runs that turned the commanded way: one that
  // turned the other way is direction-inverted's (the session's diagnosis),
  // and its size under an absolute value would hide that.
  std::vector<double> per_step;
  for (const auto& r : rep.runs) {
    const auto it = data.convs.find(r.conv);
    if (r.measured_ok && std::llabs(r.steps) >= 2 && it != data.convs.end() &&
        it->second.dialect == top::Dialect::skydroid) {
      if (r.per_step > 0 || r.ambiguous)
        per_step.push_back(std::fabs(r.per_step));
      else
        ++rep.scale_other_way;
    }
  }
  if (!per_step.empty()) {
    rep.scale_runs = per_step.size();
    rep.scale_measured = median(per_step);
    rep.scale_verdict = std::fabs(rep.scale_measured - 0.5) <= 0.1    ? ScaleVerdict::field
                        : std::fabs(rep.scale_measured - 0.1) <= 0.02 ? ScaleVerdict::document
                                                                      : ScaleVerdict::neither;
  }
  streams(data, stats, rep);
  facts(data, rep);
  return rep;
}

}  // namespace topdump::report
