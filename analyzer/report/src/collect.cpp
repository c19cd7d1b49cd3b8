// topdump report: what the sink keeps of each event (report.hpp); the
// commands that move the gimbal are kept by motion.cpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "capture/sources.hpp"
#include "report/analysis.hpp"
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
  // the time of day of format_time's calendar, to the millisecond (cut,
  // not rounded, as format_time's text reads)
  using namespace std::chrono;
  const sys_time<microseconds> tp{microseconds(ts)};
  const hh_mm_ss<microseconds> t{tp - floor<days>(tp)};
  char b[32];
  std::snprintf(
      b, sizeof b, "%02lld:%02lld:%02lld.%03lld", static_cast<long long>(t.hours().count()),
      static_cast<long long>(t.minutes().count()), static_cast<long long>(t.seconds().count()),
      static_cast<long long>(t.subseconds().count() / 1000));
  return b;
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

std::size_t latency_bin(std::int64_t us) {
  if (us <= 100) return 0;
  const double b = std::floor(5.0 * std::log10(static_cast<double>(us) / 100.0));
  return std::min(kLatencyBins - 1, static_cast<std::size_t>(std::max(0.0, b)));
}

int sev_index(top::Severity s) { return std::min(2, static_cast<int>(s)); }

}  // namespace

Example* ReportSink::finding(std::string_view code, std::optional<ACode> acode, top::Severity sev,
                             std::int64_t ts, const FrameEvent* e, std::uint32_t at,
                             const std::string& message, const std::string* sender) {
  auto known = code_at_.find(code);
  if (known == code_at_.end()) {
    auto it = codes.emplace(std::string(code), CodeStat{}).first;
    it->second.code = std::string(code);
    it->second.acode = acode;
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
  // A copy of the device's frame (fan-out) is that frame again: its
  // findings and its attitude were taken from the first.
  if (e.copy_of) return;
  const std::string* sender = e.from;
  if (e.entry && e.entry->frame) {
    const top::Frame& f = *e.entry->frame;
    const top::Decoded& d = e.entry->decoded;
    if (d.dialect != top::Dialect::unknown) c.dialect = d.dialect;
    if (d.role == top::Role::response && !e.entry->bad_checksum)
      if (const top::Model m = top::model_named_by(d.dialect, f.ident_view(), f.data());
          m != top::Model::unknown)
        c.named = m;
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
      finding(top::to_string(x.code), std::nullopt, x.severity, e.ts, &e, x.offset, x.message,
              sender);
    for (const auto& x : d.findings)
      finding(top::to_string(x.code), std::nullopt, x.severity, e.ts, &e, x.offset, x.message,
              sender);
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
    finding(to_string(n.code), n.code, n.severity, e.ts, &e, 0, n.message, sender);
}

void ReportSink::garbage(const GarbageEvent& e) {
  if (!e.item) return;
  Example* x = finding(top::to_string(e.item->finding.code), std::nullopt, e.item->finding.severity,
                       e.ts, nullptr, 0, e.item->finding.message, e.from);
  if (x) {
    x->raw = e.item->preview;
    x->record = e.pos.record;
    x->offset = e.pos.offset;
    if (e.from) x->from = *e.from;
    if (e.to) x->to = *e.to;
  }
}

void ReportSink::note(const NoteEvent& e) {
  Example* x = finding(to_string(e.note.code), e.note.code, e.note.severity, e.ts, nullptr, 0,
                       e.note.message, e.from);
  if (x) {
    x->frame = e.note.frame;
    x->record = e.pos.record;
    x->offset = e.pos.offset;
    if (e.from) x->from = *e.from;
    if (e.to) x->to = *e.to;
  }
  if (const std::optional<top::Diagnosis> dg = diagnosis_of(e.note.code)) {
    if (diagnoses.size() < kMaxDiagnosisItems)
      diagnoses.push_back({*dg, e.note.severity, e.ts, e.note.until, e.note.frame, e.note.count,
                           e.conv ? e.conv_id() : 0, file, e.note.message,
                           top::escape(std::string_view(e.note.ident, 3))});
    else
      ++diagnoses_dropped;
  }
  if (e.note.code == ACode::unanswered)
    unanswered.push_back({e.ts, e.note.frame, e.conv ? e.conv_id() : 0, file, e.note.message,
                          top::escape(std::string_view(e.note.ident, 3)), e.note.cause});
}

}  // namespace topdump::report
