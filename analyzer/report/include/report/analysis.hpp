// The analysis of a report (the report room's own header): what
// analyze() (analyze.cpp) runs over the sink's data, file by file.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "report/report.hpp"

namespace topdump::report {

// A field of a decoded frame by name, when it holds a value.
inline const top::FieldValue* field(const top::Decoded& d, std::string_view name) {
  for (const auto& f : d.fields)
    if (f.name() == name && f.valid && !f.none) return &f;
  return nullptr;
}

// printf of one number ("%.1f").
std::string fmt(const char* f, double v);

// motion.cpp: the gimbal's response to angle and rate commands.
struct Series {
  const std::vector<std::int64_t>* t = nullptr;
  const std::vector<float>* v = nullptr;
  std::string_view name;  // "GAC", "GIC", "GIA"
  bool field = false;     // read in the field's convention (top::field_convention)
};
// The times of every command (angle or rate) per axis, sorted.
using AxisTimes = std::array<std::vector<std::int64_t>, kAxes>;
AxisTimes axis_times(const ConvData& c);
// The attitude an axis command is compared with: one of its reference
// frame (Topotek GI* commands: GIC or GIA; the rest: GAC), else any seen.
Series series_for(const ConvData& c, std::string_view ident, int axis);
// The factor that puts a command's value on `axis` in the convention of
// `s`, the attitude it is compared with (up and right positive): the axis's
// sign under that attitude's convention, times `model`'s sign trait;
// `ambiguous` when the model is unknown and a trait may apply (factor 1).
int command_sign(top::Dialect d, std::string_view ident, int axis, const Series& s,
                 top::Model model, bool& ambiguous);
AngleResult angle_result(const ConvData& c, const AxisTimes& times, const AngleCommand& cmd,
                         top::Model model, double tol);
void rate_runs(const ConvData& c, const AxisTimes& times, Report& rep, std::int64_t capture_end);
// Least squares slope (deg/s) of the samples of `s` in [t0, t1]; yaw
// (`wraps`) unwrapped sample to sample, so that a pan across +-180 is one
// line (it measured a 10 deg/s pan as 7.3); `n` the samples.
bool slope(const Series& s, std::int64_t t0, std::int64_t t1, bool wraps, double& out,
           std::size_t& n);
double median(std::vector<double> v);

// streams.cpp: each stream's rate over time and its gaps.
void streams(const ReportSink& d, const Stats& st, Report& rep);

// facts.cpp: the ranked one-line facts at the top of the report.
void facts(const ReportSink& d, Report& rep);
// The causes unanswered requests are listed under, in the order their
// groups come for one identifier (the other causes are diagnoses,
// diagnosis_of, listed as such): no cause seen first, then the
// order the report has always had (its groups were once keyed by the
// causes' text, and the report's bytes stay as they were).
inline constexpr std::array<Cause, 4> kUnansweredOrder = {Cause::none, Cause::other_port,
                                                          Cause::unsupported, Cause::invalid};
// A cause's place in kUnansweredOrder; none for a cause that is a diagnosis.
std::optional<std::size_t> unanswered_rank(Cause c) noexcept;

}  // namespace topdump::report
