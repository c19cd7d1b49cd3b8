// topdump report: what the sink keeps of each event, and the analysis of
// the gimbal's response (report.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "capture/sources.hpp"
#include "report/report.hpp"

namespace topdump::report {

const char* axis_name(int axis) noexcept {
  static const char* const kNames[kAxes] = {"yaw", "pitch", "roll"};
  return axis >= 0 && axis < kAxes ? kNames[axis] : "?";
}

double latency_bin_ms(std::size_t b) noexcept {
  return 0.1 * std::pow(10.0, static_cast<double>(b) / 5.0);
}

std::string clock_text(std::int64_t ts) {
  if (ts == kNoTime) return "-";
  const std::string t = format_time(ts);  // 2024-05-01T12:00:00.123456Z
  return t.size() >= 23 ? t.substr(11, 12) : t;
}

void TimeHist::add(std::int64_t ts) {
  if (origin_ == kNoTime) {
    origin_ = ts;
    counts_.assign(kBins, 0);
  }
  if (ts < origin_) ts = origin_;  // a later file that starts earlier: at the start
  auto b = static_cast<std::uint64_t>((ts - origin_) / width_);
  while (b >= kBins) {
    for (std::size_t i = 0; i < kBins / 2; ++i) counts_[i] = counts_[2 * i] + counts_[2 * i + 1];
    std::fill(counts_.begin() + kBins / 2, counts_.end(), 0);
    width_ *= 2;
    b = static_cast<std::uint64_t>((ts - origin_) / width_);
  }
  ++counts_[b];
}

namespace {

const top::FieldValue* field(const top::Decoded& d, std::string_view name) {
  for (const auto& f : d.fields)
    if (f.name() == name && f.valid && !f.none) return &f;
  return nullptr;
}

std::size_t latency_bin(std::int64_t us) {
  if (us <= 100) return 0;
  const double b = std::floor(5.0 * std::log10(static_cast<double>(us) / 100.0));
  return std::min(kLatencyBins - 1, static_cast<std::size_t>(std::max(0.0, b)));
}

int sev_index(top::Severity s) { return std::min(2, static_cast<int>(s)); }

}  // namespace

Example* ReportSink::finding(std::string_view code, top::Severity sev, std::int64_t ts,
                             const FrameEvent* e, std::uint32_t at, const std::string& message,
                             const std::string* sender) {
  auto known = code_at_.find(code);
  if (known == code_at_.end()) {
    auto it = codes.emplace(std::string(code), CodeStat{}).first;
    it->second.code = std::string(code);
    it->second.severity = sev;
    known = code_at_.emplace(std::string_view(it->first), &it->second).first;
  }
  CodeStat& c = *known->second;
  c.severity = std::max(c.severity, sev);
  ++c.count;
  if (ts != kNoTime) {
    if (c.first == kNoTime || ts < c.first) c.first = ts;
    if (c.last == kNoTime || ts > c.last) c.last = ts;
    finding_times[static_cast<std::size_t>(sev_index(sev))].add(ts);
  }
  if (sender && !sender->empty()) {
    auto w = c.senders.find(*sender);
    if (w != c.senders.end())
      ++w->second;
    else if (c.senders.size() < 16)
      c.senders.emplace(*sender, 1);
  }
  if (c.examples.size() >= kExamples) return nullptr;
  Example x;
  x.ts = ts;
  x.file = file;
  x.at = at;
  x.message = message;
  if (e) {
    x.frame = e->n;
    x.record = e->pos.record;
    x.offset = e->pos.offset;
    if (e->from) x.from = *e->from;
    if (e->to) x.to = *e->to;
    if (e->entry && e->entry->frame) {
      x.raw = e->entry->frame->raw;
      x.decoded = std::string(e->entry->frame->ident_view());
      if (e->entry->decoded.command)
        x.decoded += " (" + std::string(e->entry->decoded.command->title) + ")";
      const std::string s = e->entry->decoded.summary();
      if (!s.empty()) x.decoded += ": " + s;
    }
  }
  c.examples.push_back(std::move(x));
  return &c.examples.back();
}

void ReportSink::frame(const FrameEvent& e) {
  if (files.empty() || files.back() != file) files.push_back(file);
  const std::uint64_t id = e.conv_id();
  if (!last_conv_ || last_conv_->id != id || last_conv_->frames == 0) last_conv_ = &convs[id];
  ConvData& c = *last_conv_;
  if (c.frames++ == 0) {
    c.id = e.conv_id();
    c.transport = e.transport;
    if (e.from) c.a = *e.from;
    if (e.to) c.b = *e.to;
  }
  const std::string* sender = e.from;
  if (e.entry && e.entry->frame) {
    const top::Frame& f = *e.entry->frame;
    const top::Decoded& d = e.entry->decoded;
    if (d.dialect != top::Dialect::unknown) c.dialect = d.dialect;
    if (d.role == top::Role::response && d.command && d.command->models && !e.entry->bad_checksum) {
      const top::ModelSet left = c.models & d.command->models;
      if (left == 0) {
        c.conflict = d.command->ident;
      } else if (left != c.models) {
        c.models = left;
        c.narrowed_by = d.command->ident;
      }
    }
    for (const auto& x : f.findings)
      finding(top::to_string(x.code), x.severity, e.ts, &e, x.offset, x.message, sender);
    for (const auto& x : d.findings)
      finding(top::to_string(x.code), x.severity, e.ts, &e, x.offset, x.message, sender);
    motion(e, c);
    if (d.role == top::Role::request) {
      Pending& p = pending[e.n % pending.size()];
      p.n = e.n;
      std::copy(f.ident, f.ident + 3, p.ident);
    }
    if (e.latency_us >= 0) {
      // keyed by the request's identifier, as the statistics are (ERE answers XYZ)
      std::string_view ident = f.ident_view();
      if (const Pending& p = pending[e.reply_to % pending.size()]; p.n == e.reply_to)
        ident = std::string_view(p.ident, 3);
      auto at = bins_at_.find(ident);
      if (at == bins_at_.end()) {
        auto it =
            latency_bins.emplace(std::string(ident), std::array<std::uint64_t, kLatencyBins>{})
                .first;
        at = bins_at_.emplace(std::string_view(it->first), &it->second).first;
      }
      auto& bins = *at->second;
      ++bins[latency_bin(e.latency_us)];
      auto later = [](const Slow& a, const Slow& b) { return a.latency_us > b.latency_us; };
      if (slowest.size() < kSlowest) {
        slowest.push_back({e.latency_us, e.reply_to, e.n, id, e.ts, std::string(ident), f.raw});
        std::push_heap(slowest.begin(), slowest.end(), later);
      } else if (e.latency_us > slowest.front().latency_us) {
        std::pop_heap(slowest.begin(), slowest.end(), later);
        slowest.back() = {e.latency_us, e.reply_to, e.n, id, e.ts, std::string(ident), f.raw};
        std::push_heap(slowest.begin(), slowest.end(), later);
      }
    }
  }
  for (const Note& n : e.notes)
    finding(to_string(n.code), n.severity, e.ts, &e, 0, n.message, sender);
}

void ReportSink::motion(const FrameEvent& e, ConvData& c) {
  const top::Frame& f = *e.entry->frame;
  const top::Decoded& d = e.entry->decoded;
  const std::string_view id = f.ident_view();
  // identifiers are three characters: compared as such, not through memcmp
  auto is = [&](const char(&x)[4]) { return id[0] == x[0] && id[1] == x[1] && id[2] == x[2]; };
  if (id[0] != 'G' && !is("PTZ") && !is("YPR") && !is("RPS")) return;
  if (id[0] == 'G' && (id[1] == 'A' || id[1] == 'I') && id[2] == 'C') {  // GAC, GIC
    // the attitude forms of both dialects: yaw, pitch, roll
    if (d.fields.size() != 3 || e.entry->bad_checksum || e.ts == kNoTime) return;
    const top::FieldValue *y = &d.fields[0], *p = &d.fields[1], *r = &d.fields[2];
    if (!y->valid || !p->valid || !r->valid || y->name() != "yaw" || p->name() != "pitch" ||
        r->name() != "roll")
      return;
    Attitude& a = c.attitude[std::string(id)];
    a.t.push_back(e.ts);
    a.v[0].push_back(static_cast<float>(y->value));
    a.v[1].push_back(static_cast<float>(p->value));
    a.v[2].push_back(static_cast<float>(r->value));
    if (e.reply_to == 0) a.push_t.push_back(e.ts);
    return;
  }
  if (d.role != top::Role::request || f.control != 'w' || e.ts == kNoTime) return;
  if (!d.command) return;
  const std::string_view cid = d.command->ident;  // static, unlike the frame's
  if (e.entry->bad_checksum) {
    if (id[0] == 'G' || is("PTZ") || is("YPR") || is("RPS"))
      c.marks.push_back({e.n, e.ts, cid, "bad checksum (dropped)"});
    return;
  }
  auto axis_of = [](char ch) { return ch == 'Y' ? 0 : ch == 'P' ? 1 : ch == 'R' ? 2 : -1; };
  auto angle = [&](int axis, const char* name, const char* speed) {
    const auto* v = field(d, name);
    if (!v || axis < 0) return;
    const auto* s = field(d, speed);
    AngleCommand a{
        e.n, e.ts, cid, axis, static_cast<float>(v->value), s ? static_cast<float>(s->value) : 0.f,
        0,   -1};
    if (v->spec) a.min = static_cast<float>(v->spec->min), a.max = static_cast<float>(v->spec->max);
    c.angles.push_back(a);
  };
  auto rate = [&](int axis, const char* name) {
    const auto* v = field(d, name);
    if (!v || axis < 0) return;
    c.rates.push_back({e.n, e.ts, cid, axis, static_cast<std::int32_t>(v->integer),
                       static_cast<float>(v->value),
                       v->spec ? static_cast<float>(v->spec->scale) : 1.f});
  };
  if (is("GAY") || is("GAP") || is("GAR") || is("GIY") || is("GIP") || is("GIR")) {
    angle(axis_of(id[2]), "angle", "speed");
  } else if (is("GAM") || is("GIM")) {
    angle(0, "yaw", "yaw_speed");
    angle(1, "pitch", "pitch_speed");
  } else if (is("GSY") || is("GSP") || is("GSR")) {
    rate(axis_of(id[2]), "speed");
  } else if (is("GSM") || is("YPR") || is("RPS")) {
    rate(0, "yaw_speed");
    rate(1, "pitch_speed");
    rate(2, "roll_speed");
  } else if (is("PTZ")) {
    const auto* a = field(d, "action");
    c.marks.push_back({e.n, e.ts, cid, a ? a->enum_name : std::string_view()});
  }
}

void ReportSink::garbage(const GarbageEvent& e) {
  if (!e.item) return;
  Example* x = finding(top::to_string(e.item->finding.code), e.item->finding.severity, e.ts,
                       nullptr, 0, e.item->finding.message, e.from);
  if (x) {
    x->raw = e.item->preview;
    x->record = e.pos.record;
    x->offset = e.pos.offset;
    if (e.from) x->from = *e.from;
    if (e.to) x->to = *e.to;
  }
}

void ReportSink::note(const NoteEvent& e) {
  Example* x =
      finding(to_string(e.note.code), e.note.severity, e.ts, nullptr, 0, e.note.message, e.from);
  if (x) {
    x->frame = e.note.frame;
    x->record = e.pos.record;
    x->offset = e.pos.offset;
    if (e.from) x->from = *e.from;
    if (e.to) x->to = *e.to;
  }
  if (e.note.code == ACode::unanswered)
    unanswered.push_back({e.ts, e.note.frame, e.conv ? e.conv_id() : 0, file, e.note.message});
}

// ---- analysis ------------------------------------------------------------

namespace {

struct Series {
  const std::vector<std::int64_t>* t = nullptr;
  const std::vector<float>* v = nullptr;
  const char* name = "";  // "GAC" or "GIC"
};

// The attitude an axis command is compared with: GIC for the earth-frame
// GI* commands (Topotek 4.3), GAC for the rest, else whichever was seen.
Series series_for(const ConvData& c, std::string_view ident, int axis) {
  const std::string want = ident.size() == 3 && ident[0] == 'G' && ident[1] == 'I' ? "GIC" : "GAC";
  auto it = c.attitude.find(want);
  if (it == c.attitude.end() || it->second.t.empty()) {
    it = c.attitude.find(want == "GAC" ? "GIC" : "GAC");
    if (it == c.attitude.end() || it->second.t.empty()) return {};
  }
  return {&it->second.t, &it->second.v[static_cast<std::size_t>(axis)],
          it->first == "GIC" ? "GIC" : "GAC"};
}

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

// The times of every command (angle or rate) per axis, sorted.
using AxisTimes = std::array<std::vector<std::int64_t>, kAxes>;

AxisTimes axis_times(const ConvData& c) {
  AxisTimes t;
  for (const auto& a : c.angles) t[static_cast<std::size_t>(a.axis)].push_back(a.t);
  for (const auto& r : c.rates) t[static_cast<std::size_t>(r.axis)].push_back(r.t);
  for (auto& v : t) std::sort(v.begin(), v.end());
  return t;
}

// When the next command on the axis comes (angle or rate), or kNoTime.
std::int64_t next_on_axis(const AxisTimes& times, int axis, std::int64_t t) {
  const auto& v = times[static_cast<std::size_t>(axis)];
  auto it = std::upper_bound(v.begin(), v.end(), t);
  return it == v.end() ? kNoTime : *it;
}

AngleResult angle_result(const ConvData& c, const AxisTimes& times, const AngleCommand& cmd,
                         const Series& s, double tol) {
  AngleResult r;
  r.cmd = &cmd;
  r.conv = c.id;
  const double eff =
      cmd.min <= cmd.max ? std::clamp<double>(cmd.target, cmd.min, cmd.max) : cmd.target;
  r.effective = static_cast<float>(eff);
  r.out_of_range = eff != cmd.target;
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
    if (end != kNoTime)
      r.superseded = true;
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

// Least squares slope (deg/s) of the samples in [t0, t1].
bool slope(const Series& s, std::int64_t t0, std::int64_t t1, double& out, std::size_t& n) {
  const std::size_t i0 = index_at(*s.t, t0), i1 = index_at(*s.t, t1 + 1);
  n = i1 > i0 ? i1 - i0 : 0;
  if (n < 3) return false;
  const double tb = static_cast<double>((*s.t)[i0]);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = i0; i < i1; ++i) {
    const double x = (static_cast<double>((*s.t)[i]) - tb) / 1e6, y = (*s.v)[i];
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double dn = static_cast<double>(n), den = dn * sxx - sx * sx;
  if (den <= 0 || (static_cast<double>((*s.t)[i1 - 1]) - tb) < 2e5) return false;
  out = (dn * sxy - sx * sy) / den;
  return true;
}

const top::Trait* refresh_trait(top::Model model, top::Dialect d) {
  if (model != top::Model::unknown)
    return top::find_trait(top::TraitKind::speed_refresh, model, top::Profile::field);
  for (const auto& t : top::traits())
    if (t.kind == top::TraitKind::speed_refresh && t.dialect == d) return &t;
  return nullptr;
}

void rate_runs(const ConvData& c, const AxisTimes& times, Report& rep, std::int64_t capture_end) {
  const top::Trait* trait = refresh_trait(rep.model, c.dialect);
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
        if (until != kNoTime && until - cmds[i]->t > limit_us)
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
      RateRun run;
      run.conv = c.id;
      run.first_frame = cmds[i]->frame;
      run.ident = std::string(cmds[i]->ident);
      run.axis = axis;
      run.start = cmds[i]->t;
      run.commands = j - i;
      run.steps = cmds[i]->steps;
      run.commanded = cmds[i]->rate;
      run.scale = cmds[i]->scale;
      run.median_interval_ms = median(intervals);
      run.max_interval_ms =
          intervals.empty() ? 0 : *std::max_element(intervals.begin(), intervals.end());
      const std::int64_t hold =
          intervals.empty() ? limit_us : static_cast<std::int64_t>(run.median_interval_ms * 1000);
      run.end = cmds[j - 1]->t + hold;
      const std::int64_t other = next_on_axis(times, axis, cmds[j - 1]->t);
      if (other != kNoTime) run.end = std::min(run.end, other);
      const Series s = series_for(c, run.ident, axis);
      // Skip the first 50 ms: the motors take a moment to reach the rate.
      if (s.t && run.steps != 0)
        run.measured_ok = slope(s, run.start + 50'000, run.end, run.measured, run.samples);
      if (run.measured_ok) run.per_step = run.measured / static_cast<double>(run.steps);
      rep.runs.push_back(run);
      i = j;
    }
  }
}

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
          if (dt > 3 * period_us) {
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

// The cause of an unanswered request, from the note's message.
std::string cause_of(const std::string& m) {
  if (m.rfind("the device was silent", 0) == 0) return "the device was silent";
  for (const char* k : {"end of the capture: ", " ms: "}) {
    const auto p = m.find(k);
    if (p != std::string::npos) return m.substr(p + std::string(k).size());
  }
  return "";
}

void facts(const ReportSink& d, Report& rep) {
  auto add = [&](int rank, top::Severity s, std::string text, std::string anchor) {
    rep.facts.push_back({rank, s, std::move(text), std::move(anchor)});
  };
  // Unanswered requests, grouped by identifier and cause.
  struct Group {
    std::uint64_t n = 0;
    std::int64_t first = kNoTime, last = kNoTime;
    std::string text;
  };
  std::map<std::string, Group> groups;
  for (const auto& u : d.unanswered) {
    const std::string cause = cause_of(u.message);
    if (cause == "the device was silent") {
      add(85, top::Severity::warning, u.message + " (from " + clock_text(u.ts) + ")", "unanswered");
      continue;
    }
    Group& g = groups[u.message.substr(0, 3) + "\x01" + cause];
    ++g.n;
    if (g.first == kNoTime) g.first = u.ts;
    g.last = u.ts;
    g.text = cause.empty() ? "no response" : cause;
  }
  for (const auto& [k, g] : groups) {
    std::string t = std::to_string(g.n) + " " + k.substr(0, 3) +
                    (g.n == 1 ? " request unanswered at " + clock_text(g.first)
                              : " requests unanswered from " + clock_text(g.first) + " to " +
                                    clock_text(g.last)) +
                    ": " + g.text;
    add(g.text == "no response" ? 80 : 60, top::Severity::warning, std::move(t), "unanswered");
  }
  // Streams off their rate or with gaps.
  for (const auto& s : rep.streams) {
    const double m = s.stat.measured_hz();
    if (s.stat.asked_hz > 0 && m > 0 && std::fabs(m - s.stat.asked_hz) > 0.25 * s.stat.asked_hz)
      add(75, top::Severity::warning,
          s.stat.ident + " push at " + fmt("%.1f", m) + " Hz, asked " + fmt("%g", s.stat.asked_hz) +
              " Hz (" + s.stat.asked_by + ", conversation " + std::to_string(s.conv) + ")",
          "streams");
    if (s.gap_count)
      add(55, top::Severity::warning,
          s.stat.ident + " push stopped " + std::to_string(s.gap_count) +
              (s.gap_count == 1 ? " time" : " times") + " for more than 3 periods; longest " +
              fmt("%.3f", s.gaps.front().ms / 1000) + " s at " + clock_text(s.gaps.front().t),
          "streams");
  }
  // Response flags, grouped by identifier.
  // per identifier: other way, never, range, superseded; the first flagged
  struct Flags {
    std::string_view id;
    std::array<std::uint64_t, 4> n{};
    std::int64_t first = kNoTime;
  };
  std::vector<Flags> all;  // a handful of identifiers: a linear search
  for (const auto& a : rep.angles) {
    auto it =
        std::find_if(all.begin(), all.end(), [&](const Flags& f) { return f.id == a.cmd->ident; });
    if (it == all.end()) it = all.insert(all.end(), Flags{a.cmd->ident});
    auto& f = it->n;
    if (a.other_way) ++f[0];
    if (a.never_reached && !a.other_way && !a.no_attitude) ++f[1];
    if (a.out_of_range) ++f[2];
    if (a.superseded && !a.other_way) ++f[3];
    if ((a.other_way || a.never_reached) && it->first == kNoTime) it->first = a.cmd->t;
  }
  std::sort(all.begin(), all.end(), [](const Flags& a, const Flags& b) { return a.id < b.id; });
  std::map<std::string_view, std::array<std::uint64_t, 4>> flags;
  std::map<std::string_view, std::int64_t> first_flag;
  for (const auto& f : all) {
    flags[f.id] = f.n;
    first_flag[f.id] = f.first;
  }
  auto plural = [](std::uint64_t n, std::string_view id) {
    return std::to_string(n) + " " + std::string(id) + (n == 1 ? " command" : " commands");
  };
  for (const auto& [id, f] : flags) {
    if (f[0]) {
      std::string t = plural(f[0], id) + " moved the gimbal the other way (sign inverted)";
      if (rep.model == top::Model::unknown || rep.model == top::Model::c12)
        for (const auto& tr : top::traits())
          if ((tr.kind == top::TraitKind::yaw_inverted && id.back() != 'P') ||
              (tr.kind == top::TraitKind::pitch_inverted && id.back() == 'P')) {
            t += "; field trait of " + std::string(top::to_string(top::Model::c12)) + ": " +
                 std::string(tr.evidence);
            break;
          }
      add(78, top::Severity::warning, std::move(t), "response");
    }
    if (f[1])
      add(70, top::Severity::warning,
          plural(f[1], id) + " never brought the gimbal within " +
              fmt("%g", rep.opts.tolerance_deg) + " deg of the target (first at " +
              clock_text(first_flag[id]) + ")",
          "response");
    if (f[2])
      add(50, top::Severity::warning,
          plural(f[2], id) + " asked for an angle outside the model's range (clamped)", "response");
    if (f[3])
      add(15, top::Severity::info, plural(f[3], id) + " superseded before the gimbal settled",
          "response");
  }
  if (!rep.gaps.empty()) {
    const auto& g =
        *std::max_element(rep.gaps.begin(), rep.gaps.end(),
                          [](const auto& a, const auto& b) { return a.gap_ms < b.gap_ms; });
    add(65, top::Severity::warning,
        std::to_string(rep.gaps.size()) + " rate command" + (rep.gaps.size() == 1 ? "" : "s") +
            " not refreshed within " + std::to_string(rep.refresh_limit_ms) + " ms (longest " +
            fmt("%.0f", g.gap_ms) + " ms after the " + g.ident + " at " + clock_text(g.t) +
            "): the motors stop",
        "rates");
  }
  if (!rep.scale_verdict.empty())
    add(25, top::Severity::info,
        "rate commands moved the gimbal at " + fmt("%.3f", rep.scale_measured) +
            " deg/s per step over " + std::to_string(rep.scale_runs) + " run" +
            (rep.scale_runs == 1 ? "" : "s") +
            (rep.scale_verdict == "0.5"   ? ": the field's 0.5 deg/s, not the document's 0.1"
             : rep.scale_verdict == "0.1" ? ": the document's 0.1 deg/s, not the field's 0.5"
                                          : ": neither the document's 0.1 nor the field's 0.5"),
        "rates");
  // Frame findings: errors and warnings by code, with who sent them.
  for (const auto& [code, c] : d.codes) {
    if (c.severity == top::Severity::info || code == "unanswered" || code == "stream-rate")
      continue;
    std::string t = code + ": " + std::to_string(c.count) + (c.count == 1 ? " time" : " times");
    if (c.senders.size() == 1)
      t += (c.count == 1 ? ", from " : ", all from ") + c.senders.begin()->first;
    else if (!c.senders.empty())
      t += ", from " + std::to_string(c.senders.size()) + " senders";
    t += " (" + clock_text(c.first) + (c.count > 1 ? " to " + clock_text(c.last) : "") + ")";
    add(c.severity == top::Severity::error ? 90 : 40, c.severity, std::move(t), "code-" + code);
  }
  std::stable_sort(rep.facts.begin(), rep.facts.end(),
                   [](const Fact& a, const Fact& b) { return a.rank > b.rank; });
}

}  // namespace

top::Dialect dialect_of(const Report& r, const ConvStats& c) {
  if (c.dialect != top::Dialect::unknown) return c.dialect;
  auto it = r.data->convs.find(c.id);
  return it == r.data->convs.end() ? c.dialect : it->second.dialect;
}

std::string model_text(top::Model given, top::Dialect d, const ConvData* c) {
  if (given != top::Model::unknown) return std::string(top::to_string(given)) + " (given)";
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
    // the attitude of each axis for GA* and GI* commands
    std::array<std::array<Series, kAxes>, 2> series;
    for (int ax = 0; ax < kAxes; ++ax) {
      series[0][static_cast<std::size_t>(ax)] = series_for(c, "GAY", ax);
      series[1][static_cast<std::size_t>(ax)] = series_for(c, "GIY", ax);
    }
    for (const auto& a : c.angles) {
      const bool earth = a.ident.size() == 3 && a.ident[1] == 'I';
      rep.angles.push_back(angle_result(c, times, a,
                                        series[earth ? 1 : 0][static_cast<std::size_t>(a.axis)],
                                        opts.tolerance_deg));
    }
    if (!c.rates.empty()) rate_runs(c, times, rep, stats.last);
  }
  std::vector<double> per_step;
  for (const auto& r : rep.runs) {
    const auto it = data.convs.find(r.conv);
    if (r.measured_ok && std::llabs(r.steps) >= 2 && it != data.convs.end() &&
        it->second.dialect == top::Dialect::skydroid)
      per_step.push_back(std::fabs(r.per_step));
  }
  if (!per_step.empty()) {
    rep.scale_runs = per_step.size();
    rep.scale_measured = median(per_step);
    rep.scale_verdict = std::fabs(rep.scale_measured - 0.5) <= 0.1    ? "0.5"
                        : std::fabs(rep.scale_measured - 0.1) <= 0.02 ? "0.1"
                                                                      : "neither";
  }
  streams(data, stats, rep);
  facts(data, rep);
  return rep;
}

}  // namespace topdump::report
