// The checks of each case (docs/DRIVE.md "The cases"), on the wire, the
// device's truth and the driver's beliefs.
#include "drive/grade.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "checks.hpp"
#include "top/decode.hpp"
#include "top/enum_names.hpp"
#include "top/frame.hpp"

namespace topconf::drive {

using namespace detail;

namespace {
constexpr std::string_view kGrade[] = {"pass",          "non-strict", "informational",
                                       "unimplemented", "fail",       "error"};
static_assert(std::size(kGrade) == static_cast<std::size_t>(Grade::error) + 1);
}  // namespace

std::string_view to_string(Grade g) noexcept { return top::enum_name(kGrade, g, "error"); }

std::optional<Grade> grade_from_string(std::string_view s) noexcept {
  return top::enum_from_name<Grade>(kGrade, s);
}

int exit_code_of(const std::vector<Grade>& grades) noexcept {
  int code = 0;
  for (Grade g : grades) {
    if (g == Grade::error) return 2;
    if (g == Grade::fail) code = 1;
  }
  return code;
}

namespace {

void stream_cases(Judge& j, const CaseSpec& c, const CaseSetup& s, const Record& r) {
  const std::string id(c.id);
  const std::vector<double> pushes = attitude_times(r);
  if (id == "1.1") {
    int early = 0;
    for (const WireFrame& w : r.wire)
      if (w.from_driver && moving(w) && (pushes.empty() || w.t < pushes.front())) ++early;
    if (early)
      j.fail(
          "no rates without attitude",
          std::to_string(early) + " rate commands sent while the device had reported no attitude");
    else
      j.pass("no rates without attitude", "none sent");
    if (healthy_in(r, 0, r.duration_s))
      j.fail("no healthy belief", "the driver believed a healthy attitude with no stream");
    else if (!r.beliefs.empty())
      j.pass("no healthy belief", "none");
    return;
  }
  bool asked = false;
  for (const WireFrame& w : r.wire) asked = asked || (w.from_driver && w.stream_on);
  if (!asked || pushes.empty()) {
    j.fail("stream switched on", "the driver never switched on the attitude stream");
    return;
  }
  if (id == "1.4") {
    const double at = r.reboot_at;
    bool before = false, again = false;
    double when = 0;
    for (const WireFrame& w : r.wire) {
      if (!w.from_driver || !w.stream_on) continue;
      before = before || w.t <= at;
      if (w.t > at && w.t <= at + 3 && !again) again = true, when = w.t;
    }
    if (!before)
      j.add(Grade::unimplemented, "stream re-enabled", false,
            "no stream switched on before the reboot at " + secs(at));
    else if (again)
      j.pass("stream re-enabled",
             "at " + secs(when) + ", " + secs(when - at) + " after the reboot");
    else
      j.fail("stream re-enabled", "not within 3 s of the reboot at " + secs(at));
    return;
  }
  if (id == "1.3") {
    // The device stops the stream fault_at after the driver first switched
    // it on.
    double first = -1, reask = -1;
    for (const WireFrame& w : r.wire)
      if (w.from_driver && w.stream_on) {
        if (first < 0)
          first = w.t;
        else if (w.t > first + s.fault_at && reask < 0)
          reask = w.t;
      }
    const double stop = first + s.fault_at;
    if (reask >= 0)
      j.pass("stream asked again", "at " + secs(reask) + ", after the stop at " + secs(stop));
    else
      j.fail("stream asked again", "never after the stream stopped at " + secs(stop));
    // Back within 2 s: no unhealthy belief needed.
    if (reask >= 0 && reask <= stop + 2.0) return;
  }
  // The stall lasts 2.2 s; a stop lasts until the driver asks again (at
  // 10 Hz, half a second without a report is it).
  const double least = id == "1.3" ? 0.5 : 1.5;
  const auto gap = longest_gap(r, 0);
  if (!gap || gap->length() < least) {
    j.add(Grade::informational, "fault", true,
          "no silence of the stream longer than " + secs(least) + ": the fault did not show");
    return;
  }
  if (r.beliefs.empty()) {
    if (id == "1.2") j.add(Grade::unimplemented, "unhealthy belief", false, "no beliefs printed");
    return;
  }
  if (unhealthy_in(r, gap->from, gap->from + 2.0))
    j.pass("unhealthy belief", "within 2 s of the last attitude at " + secs(gap->from));
  else
    j.fail("unhealthy belief", "none within 2 s of the last attitude at " + secs(gap->from));
  if (id == "1.2" && gap->to < r.duration_s - 1.0) {
    if (healthy_in(r, gap->to, gap->to + 2.0))
      j.pass("healthy again", "after the stream resumed at " + secs(gap->to));
    else
      j.fail("healthy again", "not within 2 s of the stream resuming at " + secs(gap->to));
  }
}

// 2.4: every axis turning before the stop gets a zero rate within 0.5 s
// of it, and no rate after.
void stop_case(Judge& j, const Record& r) {
  const auto go = intent_at(r, "rate"), stop = intent_at(r, "stop");
  // Per axis: the axes turning before the stop must each get a zero rate
  // within 0.5 s of it and no rate after (a GSP 0 alongside a turning
  // GSY stops nothing).
  std::array<bool, 3> turning{};
  for (const WireFrame& w : r.wire)
    if (w.from_driver && w.rate && stop && w.t < *stop)
      for (std::size_t i = 0; i < 3; ++i)
        if (w.axis[i]) turning[i] = std::abs(w.value[i]) > 1e-9;
  if (!go || !stop || moving_frames(r, 0, r.duration_s) == 0) {
    j.add(Grade::unimplemented, "zero rate after stop", false,
          "no rate command for the rate intent");
    return;
  }
  static constexpr const char* kAxis[] = {"yaw", "pitch", "roll"};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!turning[i]) continue;
    double zero = -1, late = -1;
    bool angle = false;
    for (const WireFrame& w : r.wire) {
      if (!w.from_driver || !w.axis[i]) continue;
      const bool turns = w.rate && std::abs(w.value[i]) > 1e-9;
      if (w.rate && !turns && w.t >= *stop - 0.05 && w.t <= *stop + 0.5 && zero < 0) zero = w.t;
      if (w.angle && w.t >= *stop - 0.05 && w.t <= *stop + 0.5) angle = true;
      if (turns && w.t > *stop + 0.5 && late < 0) late = w.t;
    }
    const std::string name = std::string(kAxis[i]) + " stopped";
    if (late >= 0)
      j.fail(name, "a " + std::string(kAxis[i]) + " rate at " + secs(late) +
                       ", after the stop at " + secs(*stop));
    else if (zero >= 0)
      j.pass(name, "a zero rate at " + secs(zero) + " for the stop at " + secs(*stop));
    else if (angle)
      j.add(Grade::non_strict, name, true,
            "an angle target, no zero rate, for the stop at " + secs(*stop));
    else
      j.fail(name, "no zero rate within 0.5 s of the stop at " + secs(*stop) +
                       ": the axis is left to the device's speed hold");
  }
}

void motion_cases(Judge& j, const CaseSpec& c, const Record& r) {
  const std::string id(c.id);
  const auto go = intent_at(r, "rate"), stop = intent_at(r, "stop");
  if (id == "2.1") {
    const double end = stop.value_or(r.duration_s) + 0.3;
    int cmds = 0;
    for (const WireFrame& w : r.wire)
      cmds += w.from_driver && w.t >= *go && w.t <= end && (w.rate || w.angle);
    const Truth* a = truth_at(r, *go);
    const Truth* b = truth_at(r, std::min(end, r.duration_s));
    if (cmds == 0 || !a || !b) {
      j.add(Grade::unimplemented, "pitch turns up", false,
            "no motion command for the rate intent at " + secs(*go));
      return;
    }
    const double d = b->angle[1] - a->angle[1];
    char t[160];
    std::snprintf(t, sizeof t, "pitch %.1f -> %.1f deg (%+.1f) for a pitch rate of +10 deg/s",
                  a->angle[1], b->angle[1], d);
    if (d >= 3)
      j.pass("pitch turns up", t);
    else
      j.fail("pitch turns up", t);
    return;
  }
  if (id == "2.2") {
    if (moving_frames(r, 0, r.duration_s) == 0 &&
        std::none_of(r.wire.begin(), r.wire.end(),
                     [](const WireFrame& w) { return w.from_driver && w.angle; })) {
      j.add(Grade::unimplemented, "no runaway", false, "no motion command for the angle intent");
      return;
    }
    for (const Truth& x : r.truth)
      if (x.t > 0.5 && (x.angle[1] <= x.limit_min[1] + 2 || x.angle[1] >= x.limit_max[1] - 2)) {
        char t[120];
        std::snprintf(t, sizeof t, "the pitch reached %.1f deg at %.2f s (limits %.0f..%.0f)",
                      x.angle[1], x.t, x.limit_min[1], x.limit_max[1]);
        j.fail("no runaway", t);
        return;
      }
    j.pass("no runaway", "the pitch stayed off its limits");
    if (!r.beliefs.empty()) j.beliefs(r, 0.5);
    return;
  }
  if (id == "2.3") {
    j.beliefs(r, 0.5);
    return;
  }
  if (id == "2.4") {
    stop_case(j, r);
    return;
  }
  // 2.5: no rate on an attitude older than 1.2 s
  const std::vector<double> pushes = attitude_times(r);
  int n = 0, stale = 0;
  double first = -1, age = 0;
  for (const WireFrame& w : r.wire) {
    if (!w.from_driver || !moving(w)) continue;
    ++n;
    auto it = std::upper_bound(pushes.begin(), pushes.end(), w.t);
    if (it == pushes.begin()) continue;  // before any attitude: 1.1's
    const double a = w.t - *(it - 1);
    if (a > 1.2) {
      if (stale++ == 0) first = w.t, age = a;
    }
  }
  if (n == 0)
    j.add(Grade::unimplemented, "no rates on a stale attitude", false,
          "no rate command for the rate intent");
  else if (stale)
    j.fail("no rates on a stale attitude", std::to_string(stale) +
                                               " rate commands on a stale attitude, the first at " +
                                               secs(first) + " (attitude " + secs(age) + " old)");
  else
    j.pass("no rates on a stale attitude",
           std::to_string(n) + " rate commands, all on a fresh attitude");
}

}  // namespace

Verdict grade_case(const CaseSpec& c, const CaseSetup& setup, top::Model model,
                   topsim::TransportKind link, const Record& r) {
  Judge j;
  if (!setup.not_applicable.empty()) {
    j.v.grade = Grade::informational;
    j.v.reason = setup.not_applicable;
    return j.v;
  }
  const char section = c.id[0];
  if (section == '1')
    stream_cases(j, c, setup, r);
  else if (section == '2')
    motion_cases(j, c, r);
  else
    grade_other(j, c, model, link, r);
  if (j.v.reason.empty()) j.v.reason = j.v.checks.empty() ? "nothing to check" : "every check held";
  return j.v;
}

}  // namespace topconf::drive
