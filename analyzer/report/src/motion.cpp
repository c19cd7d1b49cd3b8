// topdump report: the commands that move the gimbal (kept as the capture
// streams by), and the gimbal's response to them: angle commands settling
// or not, rate runs and their refresh, the speed scale.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "diagnoses/refresh_gap.hpp"
#include "report/analysis.hpp"
#include "report/report.hpp"

namespace topdump::report {

void ReportSink::motion(const FrameEvent& e, ConvData& c) {
  const top::Frame& f = *e.entry->frame;
  const top::Decoded& d = e.entry->decoded;
  const std::string_view id = f.ident_view();
  // What moves the gimbal, and the attitude it reports: top/motion.hpp.
  const top::MotionSpec* m = top::motion_of(d.dialect, id);
  if (m && m->kind == top::MotionKind::attitude) {
    // a report (a push or the answer to a read; a switch's echo carries no
    // angles): yaw, pitch and roll as the motion row reads them
    top::MotionReading r;
    if (f.control != 'r' || d.role == top::Role::request || !d.form || e.entry->bad_checksum ||
        e.ts == kNoTime || m->count != kAxes || !top::read_motion(*m, *d.form, f.data(), r))
      return;
    Attitude& a = c.attitude[std::string(id)];
    a.spec = m;
    a.t.push_back(e.ts);
    const bool field = top::field_convention(*m);
    for (const top::MotionAxis& x : m->fields()) {
      const auto i = static_cast<std::size_t>(x.axis);
      // (+ 0: a zero turned by the sign is 0, not -0, in the tables)
      a.v[i].push_back(static_cast<float>(r.value[i] * x.sign_in(field)) + 0.0f);
    }
    if (e.reply_to == 0) a.push_t.push_back(e.ts);
    return;
  }
  if (d.role != top::Role::request || f.control != 'w' || e.ts == kNoTime) return;
  if (!d.command) return;
  const std::string_view cid = d.command->ident;  // static, unlike the frame's
  if (e.entry->bad_checksum) {
    // the motion commands and every other G... identifier
    if (m || id[0] == 'G') c.marks.push_back({e.n, e.ts, cid, "bad checksum (dropped)"});
    return;
  }
  if (!m) return;
  if (m->kind == top::MotionKind::ptz) {
    const auto* a = field(d, "action");
    c.marks.push_back({e.n, e.ts, cid, a ? a->enum_name : std::string_view()});
    // a turn or a centring moves the gimbal: the same target sent after it
    // is a command again, not a refresh of the one held
    const top::PtzAction act = top::ptz_action(a && a->valid ? a->integer : -1);
    if (act.move == top::PtzMove::turn) c.held[static_cast<std::size_t>(act.axis)] = -1;
    if (act.move == top::PtzMove::centre) c.held.fill(-1);
    return;
  }
  // axis by axis, yaw first, as the rates and angles are listed
  for (std::size_t axis = 0; axis < top::axis_count; ++axis)
    for (const top::MotionAxis& x : m->fields()) {
      if (static_cast<std::size_t>(x.axis) != axis) continue;
      const auto* v = field(d, x.value);
      if (!v) continue;
      const int ax = static_cast<int>(axis);
      if (m->kind == top::MotionKind::angle) {
        const auto* s = field(d, x.speed);
        AngleCommand a{e.n,
                       e.ts,
                       cid,
                       ax,
                       static_cast<float>(v->value),
                       s ? static_cast<float>(s->value) : 0.f,
                       0,
                       -1};
        if (v->spec)
          a.min = static_cast<float>(v->spec->min), a.max = static_cast<float>(v->spec->max);
        std::ptrdiff_t& held = c.held[axis];
        if (held >= 0) {
          AngleCommand& h = c.angles[static_cast<std::size_t>(held)];
          if (h.ident == a.ident && h.target == a.target && h.speed == a.speed) {
            ++h.commands;  // a refresh of the target held
            continue;
          }
        }
        held = static_cast<std::ptrdiff_t>(c.angles.size());
        c.angles.push_back(a);
      } else {
        c.held[axis] = -1;
        c.rates.push_back({e.n, e.ts, cid, ax, static_cast<std::int32_t>(v->integer),
                           static_cast<float>(v->value),
                           v->spec ? static_cast<float>(v->spec->scale) : 1.f});
      }
    }
}

Series series_for(const ConvData& c, std::string_view ident, int axis) {
  const top::MotionSpec* m = top::motion_of(c.dialect, ident);
  const top::Reference want = m ? m->reference : top::Reference::body;
  const std::pair<const std::string, Attitude>* best = nullptr;
  for (const auto& kv : c.attitude) {
    const Attitude& a = kv.second;
    if (a.t.empty() || !a.spec) continue;
    if (!best || (a.spec->reference == want && best->second.spec->reference != want)) best = &kv;
  }
  if (!best) return {};
  return {&best->second.t, &best->second.v[static_cast<std::size_t>(axis)], best->first,
          top::field_convention(*best->second.spec)};
}

int command_sign(top::Dialect d, std::string_view ident, int axis, const Series& s,
                 top::Model model, bool& ambiguous) {
  ambiguous = false;
  const top::MotionSpec* m = top::motion_of(d, ident);
  if (!m) return 1;
  int sign = 1;
  for (const top::MotionAxis& x : m->fields())
    if (static_cast<int>(x.axis) == axis) sign = x.sign_in(s.field);
  const int t = top::sign_trait_factor(d, model, axis, ident);
  ambiguous = t == 0;
  return t == 0 ? sign : sign * t;
}

namespace {

std::size_t index_at(const std::vector<std::int64_t>& t, std::int64_t ts) {
  return static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), ts) - t.begin());
}

// The first sample of [i0, i1) from which every later one stays within
// `tol` of `target` (i1: none).
std::size_t settle_index(const Series& s, std::size_t i0, std::size_t i1, double target,
                         double tol) {
  std::size_t k = i1;
  while (k > i0 && std::fabs((*s.v)[k - 1] - target) <= tol) --k;
  return k;
}

}  // namespace

AxisTimes axis_times(const ConvData& c) {
  AxisTimes t;
  for (const auto& a : c.angles) t[static_cast<std::size_t>(a.axis)].push_back(a.t);
  for (const auto& r : c.rates) t[static_cast<std::size_t>(r.axis)].push_back(r.t);
  for (auto& v : t) std::sort(v.begin(), v.end());
  return t;
}

namespace {

// When the next command on the axis comes (angle or rate), or kNoTime.
std::int64_t next_on_axis(const AxisTimes& times, int axis, std::int64_t t) {
  const auto& v = times[static_cast<std::size_t>(axis)];
  auto it = std::upper_bound(v.begin(), v.end(), t);
  return it == v.end() ? kNoTime : *it;
}

}  // namespace

AngleResult angle_result(const ConvData& c, const AxisTimes& times, const AngleCommand& cmd,
                         top::Model model, double tol) {
  AngleResult r;
  r.cmd = &cmd;
  r.conv = c.id;
  const Series s = series_for(c, cmd.ident, cmd.axis);
  const double clamped =
      cmd.min <= cmd.max ? std::clamp<double>(cmd.target, cmd.min, cmd.max) : cmd.target;
  r.out_of_range = clamped != cmd.target;
  const double eff = clamped * command_sign(c.dialect, cmd.ident, cmd.axis, s, model, r.ambiguous);
  r.effective = static_cast<float>(eff);
  const std::int64_t end = next_on_axis(times, cmd.axis, cmd.t);
  if (!s.t) {
    r.no_attitude = true;
    return r;
  }
  r.attitude = s.name;
  const std::size_t i0 = index_at(*s.t, cmd.t);
  const std::size_t i1 = end == kNoTime ? s.t->size() : index_at(*s.t, end);
  r.samples = static_cast<std::uint32_t>(i1 > i0 ? i1 - i0 : 0);
  if (r.samples == 0) {
    r.no_attitude = true;
    r.superseded = end != kNoTime;
    return r;
  }
  const std::vector<float>& v = *s.v;
  const double start = i0 > 0 ? v[i0 - 1] : v[i0];
  r.start = static_cast<float>(start);
  const double step = eff - start;
  auto secs = [&](std::size_t k) {
    return static_cast<float>(static_cast<double>((*s.t)[k] - cmd.t) / 1e6);
  };
  if (cmd.speed > 0) r.expected_s = static_cast<float>(std::fabs(step) / cmd.speed);
  const std::size_t k = settle_index(s, i0, i1, eff, tol);
  if (k < i1) r.settling_s = secs(k);
  const std::size_t tail = std::min<std::size_t>(5, r.samples);
  double last = 0;
  for (std::size_t i = i1 - tail; i < i1; ++i) last += v[i];
  last /= static_cast<double>(tail);
  r.final_error = static_cast<float>(last - eff);
  if (std::fabs(step) > tol) {
    const double dir = step > 0 ? 1 : -1;
    double over = 0;
    for (std::size_t i = i0; i < i1; ++i) over = std::max(over, dir * (v[i] - eff));
    r.overshoot_deg = static_cast<float>(over);
    r.overshoot_pct = static_cast<float>(100.0 * over / std::fabs(step));
    const double moved = v[i1 - 1] - start;
    if (dir * moved < -tol) {
      // moving the other way is not overshoot: settling against -target
      r.other_way = true;
      r.overshoot_deg = r.overshoot_pct = 0;
      const std::size_t m = settle_index(s, i0, i1, -eff, tol);
      if (m < i1) r.mirrored_settling_s = secs(m);
    }
  }
  if (r.settling_s < 0) {
    // The capture's end cut short a gimbal still on its way: within the
    // time its speed needs, or its last half second still closing in.
    const std::size_t back = i1 - std::min<std::size_t>(i1 - i0, 6);
    const bool closing = std::fabs(step) > tol && (step > 0 ? 1 : -1) * (v[i1 - 1] - v[back]) > tol;
    const bool in_time = r.expected_s >= 0 && secs(i1 - 1) < r.expected_s * 1.25f + 0.5f;
    if (end != kNoTime)
      r.superseded = true;
    else if (!r.other_way && (closing || in_time))
      r.still_moving = true;
    else
      r.never_reached = true;
  }
  return r;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

namespace {}  // namespace

bool slope(const Series& s, std::int64_t t0, std::int64_t t1, bool wraps, double& out,
           std::size_t& n) {
  const std::size_t i0 = index_at(*s.t, t0), i1 = index_at(*s.t, t1 + 1);
  n = i1 > i0 ? i1 - i0 : 0;
  if (n < 3) return false;
  const double tb = static_cast<double>((*s.t)[i0]);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  double y = (*s.v)[i0];
  for (std::size_t i = i0; i < i1; ++i) {
    if (i > i0) {
      const double d = double{(*s.v)[i]} - (*s.v)[i - 1];
      y += wraps ? top::short_way(d) : d;
    }
    const double x = (static_cast<double>((*s.t)[i]) - tb) / 1e6;
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double dn = static_cast<double>(n), den = dn * sxx - sx * sx;
  if (den <= 0 || (static_cast<double>((*s.t)[i1 - 1]) - tb) < 2e5) return false;
  out = (dn * sxy - sx * sy) / den;
  return true;
}

void rate_runs(const ConvData& c, const AxisTimes& times, Report& rep, std::int64_t capture_end) {
  const top::Trait* trait = top::speed_refresh_trait(rep.model, c.dialect);
  const std::int64_t limit_us = trait ? std::int64_t{trait->value} * 1000 : 1'000'000;
  if (trait) {
    rep.refresh_limit_ms = trait->value;
    rep.refresh_evidence = std::string(trait->evidence);
  }
  for (int axis = 0; axis < kAxes; ++axis) {
    std::vector<const RateCommand*> cmds;
    for (const auto& r : c.rates)
      if (r.axis == axis) cmds.push_back(&r);
    if (cmds.empty()) continue;
    for (std::size_t i = 0; i < cmds.size(); ++i) {
      const std::int64_t next = i + 1 < cmds.size() ? cmds[i + 1]->t : kNoTime;
      const std::int64_t other = next_on_axis(times, axis, cmds[i]->t);
      if (trait && cmds[i]->steps != 0 && (other == kNoTime || other == next)) {
        const std::int64_t until = next != kNoTime ? next : capture_end;
        if (until != kNoTime && diag::refresh_missed(until - cmds[i]->t, limit_us))
          rep.gaps.push_back({c.id, cmds[i]->frame, std::string(cmds[i]->ident), cmds[i]->t,
                              static_cast<double>(until - cmds[i]->t) / 1000.0});
      }
    }
    std::size_t i = 0;
    while (i < cmds.size()) {
      std::size_t j = i + 1;
      std::vector<double> intervals;
      while (j < cmds.size() && cmds[j]->steps == cmds[i]->steps &&
             cmds[j]->t - cmds[j - 1]->t <= limit_us) {
        intervals.push_back(static_cast<double>(cmds[j]->t - cmds[j - 1]->t) / 1000.0);
        ++j;
      }
      const Series s = series_for(c, cmds[i]->ident, axis);
      RateRun run;
      run.sign = command_sign(c.dialect, cmds[i]->ident, axis, s, rep.model, run.ambiguous);
      run.conv = c.id;
      run.first_frame = cmds[i]->frame;
      run.ident = std::string(cmds[i]->ident);
      run.axis = axis;
      run.start = cmds[i]->t;
      run.commands = j - i;
      run.steps = cmds[i]->steps;
      // in the unit field evidence gives where the attitude follows the
      // field's convention (Topotek YPR: 0.8192 deg/s a count, FIELD.md)
      const top::MotionSpec* ms = top::motion_of(c.dialect, cmds[i]->ident);
      const double rate = static_cast<double>(cmds[i]->rate);
      run.commanded =
          (ms ? top::motion_speed(*ms, rate, cmds[i]->steps, s.field) : rate) * run.sign;
      run.scale = cmds[i]->scale;
      run.median_interval_ms = median(intervals);
      run.max_interval_ms =
          intervals.empty() ? 0 : *std::max_element(intervals.begin(), intervals.end());
      const std::int64_t hold =
          intervals.empty() ? limit_us : static_cast<std::int64_t>(run.median_interval_ms * 1000);
      run.end = cmds[j - 1]->t + hold;
      const std::int64_t other = next_on_axis(times, axis, cmds[j - 1]->t);
      if (other != kNoTime) run.end = std::min(run.end, other);
      // Skip the first 50 ms: the motors take a moment to reach the rate.
      if (s.t && run.steps != 0)
        run.measured_ok =
            slope(s, run.start + 50'000, run.end, axis == static_cast<int>(top::Axis::yaw),
                  run.measured, run.samples);
      if (run.measured_ok) run.per_step = run.measured / static_cast<double>(run.steps * run.sign);
      rep.runs.push_back(run);
      i = j;
    }
  }
}

}  // namespace topdump::report
