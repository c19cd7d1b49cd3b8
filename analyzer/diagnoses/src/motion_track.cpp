#include "diagnoses/motion_track.hpp"

#include <algorithm>
#include <cmath>

#include "top/device.hpp"
#include "top/diagnoses.hpp"

namespace topdump::diag {

namespace {

int sign_of(std::int64_t v) noexcept { return v > 0 ? 1 : v < 0 ? -1 : 0; }

const top::MotionAxis* axis_of(const top::MotionSpec& m, int axis) noexcept {
  for (const top::MotionAxis& a : m.fields())
    if (static_cast<int>(a.axis) == axis) return &a;
  return nullptr;
}

// The direction of each axis of a rate command (the raw sign); false when
// its data does not read.
bool read_signs(const top::MotionSpec& m, const top::FormSpec* form, std::string_view data,
                std::array<int, top::axis_count>& out) {
  top::MotionReading r;
  if (!form || !top::read_motion(m, *form, data, r)) return false;
  for (std::size_t i = 0; i < top::axis_count; ++i) out[i] = sign_of(r.raw[i]);
  return true;
}

}  // namespace

bool Snap::angle(int axis, double& out) const noexcept {
  top::MotionReading r;
  if (!spec || !form || !top::read_motion(*spec, *form, view(), r, axis)) return false;
  const top::MotionAxis* a = axis_of(*spec, axis);
  if (!a || !r.has[static_cast<std::size_t>(axis)]) return false;
  out = r.value[static_cast<std::size_t>(axis)] * a->sign_in(top::field_convention(*spec));
  return true;
}

bool Snap::turned(const Snap& a, double ya, const Snap& b, double yb, double& out) noexcept {
  if (a.u.epoch == 0 || a.u.epoch != b.u.epoch) return false;
  // each reading is within a mark's step of its mark: the short way there
  out = (b.u.turned + top::short_way(yb - double{b.u.yaw})) -
        (a.u.turned + top::short_way(ya - double{a.u.yaw}));
  return true;
}

void MotionTrack::mark(std::size_t slot) {
  Unwrap& u = unwrap_[slot];
  const Snap& m = marks_[slot][1];
  const Snap& before = marks_[slot][0];
  double y = 0;
  if (!m.angle(static_cast<int>(top::Axis::yaw), y)) {
    u.epoch = 0;
    return;
  }
  if (u.epoch != 0 && before.spec == m.spec) {
    u.turned = static_cast<float>(u.turned + top::short_way(y - double{u.yaw}));
  } else {
    u.epoch = ++epochs_;
    u.turned = static_cast<float>(y);
  }
  u.yaw = static_cast<float>(y);
}

int MotionTrack::ref_for(const top::MotionSpec& m) const noexcept {
  const int want = m.reference == top::Reference::earth ? 1 : 0;
  return att_[static_cast<std::size_t>(want)].set() ||
                 !att_[static_cast<std::size_t>(1 - want)].set()
             ? want
             : 1 - want;
}

void MotionTrack::command(const top::MotionSpec& m, const top::FormSpec* form,
                          std::string_view data, std::uint64_t n, std::int64_t ts, int dir) {
  const bool stale = reports_ >= StaleWatch::kMinReports && ts - last_report_ > kStaleUs;
  if (m.kind == top::MotionKind::ptz) {
    const top::PtzAction a = top::ptz_action(form ? top::ptz_code(*form, data) : -1);
    if (a.move == top::PtzMove::stop || a.move == top::PtzMove::centre) {
      for (Window& w : win_) {
        if (!w.cmd.spec) continue;  // none open (a stop repeated)
        check_refresh(w, ts);
        close(w);
        w.cmd.spec = nullptr;
      }
    } else if (a.move == top::PtzMove::turn) {
      if (stale) stale_.command(n, ts, m.ident, dir, last_report_, last_attitude_->ident);
      on_axis(static_cast<int>(a.axis), a.sign, m, form, data, n, ts, dir);
    }
    return;
  }
  // Angles are read only when judged; rates for their direction, unless
  // every axis's window has this very data (a refresh).
  std::array<int, top::axis_count> sign{};
  if (stale || m.kind == top::MotionKind::rate) {
    bool refresh = !stale;
    for (const top::MotionAxis& a : m.fields())
      refresh = refresh && win_[static_cast<std::size_t>(a.axis)].cmd.same(m, data);
    if (!refresh && !read_signs(m, form, data, sign)) return;
    if (stale && std::any_of(sign.begin(), sign.end(), [](int v) { return v != 0; }))
      stale_.command(n, ts, m.ident, dir, last_report_, last_attitude_->ident);
  }
  for (const top::MotionAxis& a : m.fields()) {
    const auto i = static_cast<std::size_t>(a.axis);
    on_axis(static_cast<int>(a.axis), m.kind == top::MotionKind::rate ? sign[i] : 0, m, form, data,
            n, ts, dir);
  }
}

void MotionTrack::on_axis(int axis, int sign, const top::MotionSpec& m, const top::FormSpec* form,
                          std::string_view data, std::uint64_t n, std::int64_t ts, int dir) {
  Window& w = win_[static_cast<std::size_t>(axis)];
  if (m.kind == top::MotionKind::rate) check_refresh(w, ts);
  auto refresh = [&] {
    w.last_ts = ts;
    w.last_n = n;
    ++w.commands;
    // where the attitude was at the last command (axis-left-moving: rates)
    if (m.kind != top::MotionKind::angle) w.at_last = att_[static_cast<std::size_t>(w.ref)];
  };
  if (w.cmd.same(m, data)) return refresh();
  if (w.cmd.spec == &m &&
      (m.kind == top::MotionKind::angle ? ts - w.open_ts < kMinWindow : sign == w.sign)) {
    w.cmd.take(m, form, data, ts);  // a new target or speed, the same window
    return refresh();
  }
  close(w);
  w.cmd.spec = nullptr;
  if (!w.cmd.take(m, form, data, ts)) return;
  w.acked = false;
  w.ref = ref_for(m);
  w.start = att_[static_cast<std::size_t>(w.ref)];
  // where the attitude was at the last command: rates and PTZ only
  // (axis-left-moving; an angle window's is never read)
  if (m.kind != top::MotionKind::angle) w.at_last = w.start;
  w.open_ts = w.last_ts = ts;
  w.first_n = w.last_n = n;
  w.commands = 1;
  w.dir = dir;
  w.sign = sign;
}

void MotionTrack::check_refresh(const Window& w, std::int64_t ts) {
  const top::MotionSpec* m = w.cmd.spec;
  if (!m || m->kind != top::MotionKind::rate || w.sign == 0) return;
  if (refresh_limit_us_ < 0) {
    const top::Trait* t =
        top::speed_refresh_trait(model_ != top::Model::unknown ? model_ : named_, m->dialect);
    refresh_limit_us_ = t ? std::int64_t{t->value} * 1000 : 0;
  }
  if (refresh_missed(ts - w.last_ts, refresh_limit_us_))
    refresh_.gap(w.last_n, w.last_ts, m->ident, static_cast<int>(&w - win_.data()), w.dir,
                 ts - w.last_ts, static_cast<std::uint32_t>(refresh_limit_us_ / 1000));
}

WindowOf MotionTrack::window_of(const Window& w) const noexcept {
  return {w.cmd.spec, static_cast<int>(&w - win_.data()), w.dir,
          att_[static_cast<std::size_t>(w.ref)].spec->ident};
}

void MotionTrack::judge(const Window& w) {
  const top::MotionSpec* m = w.cmd.spec;
  const Snap& end = att_[static_cast<std::size_t>(w.ref)];
  const int axis = static_cast<int>(&w - win_.data());
  Judged j{window_of(w)};
  j.first_n = w.first_n;
  j.commands = w.commands;
  j.open_ts = w.open_ts;
  j.acked = w.acked;
  j.seconds = static_cast<double>(end.ts - w.start.ts) / 1e6;
  if (!w.start.angle(axis, j.from) || !end.angle(axis, j.to)) return;
  if (axis == static_cast<int>(top::Axis::yaw))
    j.whole = Snap::turned(w.start, j.from, end, j.to, j.turned);
  const bool field = top::field_convention(*end.spec);
  if (m->kind == top::MotionKind::ptz) {
    j.sign = w.sign;
  } else {
    top::MotionReading r;
    const top::MotionAxis* a = axis_of(*m, axis);
    if (!a || !top::read_motion(*m, *w.cmd.form, w.cmd.view(), r, axis)) return;
    const auto i = static_cast<std::size_t>(axis);
    const int s = a->sign_in(field);
    j.raw = r.raw[i];
    // the model's sign trait: a C12 turns GAY +10 to GAC yaw -10 (docs/FIELD.md)
    const int t = top::sign_trait_factor(m->dialect, model_, axis, m->ident);
    j.ambiguous = t == 0;
    j.sign = sign_of(r.raw[i]) * s * (t == 0 ? 1 : t);
    double target = r.value[i];
    if (r.min[i] <= r.max[i]) target = std::clamp(target, r.min[i], r.max[i]);
    j.linear = m->kind == top::MotionKind::angle && axis == static_cast<int>(top::Axis::yaw) &&
               r.min[i] <= r.max[i] && r.max[i] - r.min[i] < 359.0;
    j.target = target * s * (t == 0 ? 1 : t);
    j.wire = m->kind == top::MotionKind::angle
                 ? r.value[i]
                 : std::fabs(top::motion_speed(*m, r.value[i], r.raw[i], field));
    j.field_sign = static_cast<std::int8_t>(s);
    j.trait = static_cast<std::int8_t>(t == 0 ? 1 : t);
  }
  direction_.window(j);
  ignored_.window(j);
}

void MotionTrack::handover() {
  tracking_ = true;
  for (Window& w : win_) {
    close(w);
    w.cmd.spec = nullptr;
  }
}

void MotionTrack::finish(std::int64_t end_ts) {
  for (Window& w : win_) {
    const top::MotionSpec* m = w.cmd.spec;
    const auto ref = static_cast<std::size_t>(w.ref);
    const Snap& end = att_[ref];
    if (m && m->kind != top::MotionKind::angle && w.sign != 0 && w.at_last.set() &&
        end.spec == w.at_last.spec) {
      const auto& mk = marks_[ref];
      const Snap& mark = mk[1].set() && end.ts - mk[1].ts >= kMinWindow ? mk[1] : mk[0];
      LeftMoving lm{window_of(w)};
      lm.last_n = w.last_n;
      lm.last_ts = w.last_ts;
      lm.mark_ts = mark.ts;
      lm.end_ts = end.ts;
      const top::MotionAxis* a = axis_of(*m, lm.axis);
      lm.sign = a ? w.sign * a->sign_in(top::field_convention(*end.spec)) : w.sign;
      top::MotionReading r;
      if (a && top::read_motion(*m, *w.cmd.form, w.cmd.view(), r)) {
        const auto i = static_cast<std::size_t>(lm.axis);
        lm.raw = r.raw[i];
        lm.speed = std::fabs(
            top::motion_speed(*m, r.value[i], r.raw[i], top::field_convention(*end.spec)));
      }
      // Reports that read the same at the end: stopped (a motor stopped by
      // the refresh limit within the last mark's half second read as
      // "still moving" over it)
      const bool stopped = changed_[ref] != kNoTime && end.ts - changed_[ref] >= kStoppedUs;
      if (!stopped && mark.spec == end.spec && w.at_last.angle(lm.axis, lm.at_last) &&
          mark.angle(lm.axis, lm.at_mark) && end.angle(lm.axis, lm.at_end)) {
        if (lm.axis == static_cast<int>(top::Axis::yaw))
          lm.whole = Snap::turned(w.at_last, lm.at_last, end, lm.at_end, lm.after);
        left_.at_end(lm);
      }
    }
    // The gap to the end is no refresh-gap when the axis kept moving to the
    // end: the motors did not stop, whatever the model's limit says (an
    // outside capture read both "still +20.0 deg/s at the end" and "the
    // motors stop" of one axis).
    const int axis = static_cast<int>(&w - win_.data());
    if (end_ts != kNoTime && !left_.found(axis)) check_refresh(w, end_ts);
    close(w);
    w.cmd.spec = nullptr;
  }
}

}  // namespace topdump::diag
