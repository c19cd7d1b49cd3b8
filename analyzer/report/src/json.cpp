// topdump report --json: the analysis of report.hpp as one JSON document,
// through the one JSON writer (json_writer.hpp). Keys: docs/REPORT.md.
#include <cmath>

#include "output/json_writer.hpp"
#include "report/report.hpp"
#include "top/detail/text.hpp"

namespace topdump::report {

using namespace jsonw;

namespace {

// A measure rounded to 1e-4 (null when negative: not measured).
void put_measure(std::string& o, double v, bool null_if_negative = true) {
  if (null_if_negative && v < 0)
    app(o, "null");
  else
    put_double(o, std::round(v * 1e4) / 1e4);
}

}  // namespace

namespace {

// The document's writer: the value helpers and one function per section.
struct Writer {
  Doc& j;
  std::string& o;
  const Report& r;
  const ReportSink& d;
  const Stats& s;

  void num(std::string_view k, double v) {  // any value
    j.key(k);
    put_measure(o, v, false);
  }
  void opt(std::string_view k, double v) {  // negative: not measured
    j.key(k);
    put_measure(o, v);
  }
  void u(std::string_view k, std::uint64_t v) {
    j.key(k);
    put_u(o, v);
  }
  void text(std::string_view k, std::string_view v) {
    j.key(k);
    put_str(o, v);
  }
  void time(std::string_view k, std::int64_t v) {
    j.key(k);
    put_time(o, v);
  }
  void overview();
  void angles();
  void rates();
  void latency();
  void streams();
  void findings();
  void unanswered();
};

void Writer::overview() {
  j.key_object("overview");
  j.key_array("files");
  for (const auto& f : r.opts.files) {
    j.item();
    put_str(o, f);
  }
  j.close_array();
  u("frames", s.frames);
  time("first_time", s.first);
  time("last_time", s.last);
  text("worst", top::to_string(r.worst));
  text("model", top::to_string(r.model));
  num("tolerance_deg", r.opts.tolerance_deg);
  j.key_array("conversations");
  for (const ConvStats& c : s.conversations) {
    j.item_object();
    u("id", c.id);
    text("transport", to_string(c.transport));
    text("a", c.a);
    text("b", c.b);
    text("dialect", top::to_string(dialect_of(r, c)));
    text("model", model_text(r, c));
    u("frames", c.frames);
    j.close_object();
  }
  j.close_array();
  j.key_array("what_went_wrong");
  for (const Fact& f : r.facts) {
    j.item_object();
    text("severity", top::to_string(f.severity));
    j.key("code");
    if (f.code)
      put_str(o, top::to_string(*f.code));
    else
      o += "null";
    text("text", f.text);
    text("section", f.anchor);
    if (f.code) {
      text("evidence", top::evidence(*f.code));
      text("remedy", top::remedy(*f.code));
      j.key("frame");
      if (f.frame)
        put_u(o, f.frame);
      else
        o += "null";
      u("count", f.count);
    }
    j.close_object();
  }
  j.close_array();
  j.close_object();
}

void Writer::angles() {
  j.key_array("angle_commands");
  for (const AngleResult& a : r.angles) {
    j.item_object();
    u("conversation", a.conv);
    u("frame", a.cmd->frame);
    time("time", a.cmd->t);
    text("ident", a.cmd->ident);
    text("axis", axis_name(a.cmd->axis));
    u("commands", a.cmd->commands);
    num("target_deg", a.cmd->target);
    j.key("speed_deg_s");
    if (a.cmd->speed > 0)
      put_measure(o, a.cmd->speed);
    else
      app(o, "null");
    text("attitude", a.attitude);
    u("samples", a.samples);
    num("start_deg", a.start);
    num("effective_target_deg", a.effective);
    opt("expected_s", a.expected_s);
    opt("settling_s", a.settling_s);
    j.key("overshoot_deg");
    put_measure(o, a.overshoot_deg, false);
    j.key("overshoot_pct");
    put_measure(o, a.overshoot_pct, false);
    j.key("steady_state_error_deg");
    put_measure(o, a.final_error, false);
    j.key_array("flags");
    auto f = [&](bool on, const char* name) {
      if (!on) return;
      j.item();
      put_str(o, name);
    };
    f(a.no_attitude, "no-attitude");
    f(a.still_moving, "still-moving");
    f(a.never_reached, "never-reached");
    f(a.other_way, "other-way");
    f(a.out_of_range, "out-of-range");
    f(a.superseded, "superseded");
    j.close_array();
    opt("mirrored_settling_s", a.mirrored_settling_s);
    j.close_object();
  }
  j.close_array();
}

void Writer::rates() {
  j.key_object("rate_commands");
  j.key("refresh_limit_ms");
  if (r.refresh_limit_ms)
    put_i(o, r.refresh_limit_ms);
  else
    app(o, "null");
  text("refresh_evidence", r.refresh_evidence);
  text("scale_verdict", to_string(r.scale_verdict));
  opt("measured_deg_s_per_step", r.scale_runs ? r.scale_measured : -1);
  u("scale_runs", r.scale_runs);
  u("scale_other_way_runs", r.scale_other_way);
  j.key_array("runs");
  for (const RateRun& x : r.runs) {
    j.item_object();
    u("conversation", x.conv);
    u("frame", x.first_frame);
    text("ident", x.ident);
    text("axis", axis_name(x.axis));
    time("start", x.start);
    time("end", x.end);
    u("commands", x.commands);
    j.key("steps");
    put_i(o, x.steps);
    j.key("commanded_deg_s");
    put_measure(o, x.commanded, false);
    j.key("catalog_deg_s_per_step");
    put_measure(o, x.scale, false);
    j.key("median_refresh_ms");
    put_measure(o, x.median_interval_ms, false);
    j.key("max_refresh_ms");
    put_measure(o, x.max_interval_ms, false);
    u("samples", x.samples);
    j.key("measured_deg_s");
    if (x.measured_ok)
      put_measure(o, x.measured, false);
    else
      app(o, "null");
    j.key("measured_deg_s_per_step");
    if (x.measured_ok)
      put_measure(o, x.per_step, false);
    else
      app(o, "null");
    j.close_object();
  }
  j.close_array();
  j.key_array("refresh_gaps");
  for (const RefreshGap& g : r.gaps) {
    j.item_object();
    u("conversation", g.conv);
    u("frame", g.frame);
    text("ident", g.ident);
    time("time", g.t);
    j.key("gap_ms");
    put_measure(o, g.gap_ms, false);
    j.close_object();
  }
  j.close_array();
  j.close_object();
}

void Writer::latency() {
  j.key_object("latency");
  for (const auto& [ident, l] : s.latency) {
    j.key_object(ident);
    latency_members(j, l);
    j.key_array("histogram");
    auto it = d.latency_bins.find(ident);
    if (it != d.latency_bins.end())
      for (std::size_t b = 0; b < kLatencyBins; ++b) {
        if (!it->second[b]) continue;
        j.item_object();
        j.key("from_ms");
        put_measure(o, latency_bin_ms(b), false);
        u("count", it->second[b]);
        j.close_object();
      }
    j.close_array();
    j.close_object();
  }
  j.key_array("slowest");
  std::vector<Slow> slow = d.slowest;
  std::sort(slow.begin(), slow.end(),
            [](const Slow& a, const Slow& b) { return a.latency_us > b.latency_us; });
  for (const Slow& x : slow) {
    j.item_object();
    text("ident", x.ident);
    j.key("latency_ms");
    put_measure(o, static_cast<double>(x.latency_us) / 1000.0, false);
    u("request", x.request);
    u("response", x.response);
    u("conversation", x.conv);
    time("time", x.ts);
    j.key("response_raw");
    put_esc(o, x.response_raw);
    j.close_object();
  }
  j.close_array();
  j.close_object();
}

void Writer::streams() {
  j.key_array("streams");
  for (const StreamResult& x : r.streams) {
    j.item_object();
    u("conversation", x.conv);
    stream_members(j, x.stat, StreamKeys{.asked_by = true, .measured_per_hz = 1e4});
    j.key("bucket_s");
    put_double(o, static_cast<double>(x.bucket_us) / 1e6);
    j.key_array("rate_hz");
    for (float v : x.rate) {
      j.item();
      put_measure(o, v, false);
    }
    j.close_array();
    u("gap_count", x.gap_count);
    j.key_array("gaps");
    for (const auto& g : x.gaps) {
      j.item_object();
      time("time", g.t);
      j.key("ms");
      put_measure(o, g.ms, false);
      j.close_object();
    }
    j.close_array();
    j.close_object();
  }
  j.close_array();
}

void Writer::findings() {
  j.key_array("findings");
  for (const auto& [code, c] : d.codes) {
    j.item_object();
    text("code", code);
    text("severity", top::to_string(c.severity));
    u("count", c.count);
    time("first", c.first);
    time("last", c.last);
    j.key_object("senders");
    for (const auto& [who, n] : c.senders) u(who, n);
    j.close_object();
    j.key_array("examples");
    for (const Example& x : c.examples) {
      j.item_object();
      text("file", x.file);
      u("frame", x.frame);
      time("time", x.ts);
      u("record", x.record);
      u("record_offset", x.offset);
      u("finding_offset", x.at);
      text("from", x.from);
      text("to", x.to);
      j.key("raw");
      put_esc(o, x.raw);
      j.key("decoded");
      put_str(o, top::ascii_text(x.decoded));
      j.key("message");
      put_str(o, top::ascii_text(x.message));
      j.close_object();
    }
    j.close_array();
    j.close_object();
  }
  j.close_array();
}

void Writer::unanswered() {
  j.key_array("unanswered");
  for (const Unanswered& x : d.unanswered) {
    j.item_object();
    time("time", x.ts);
    u("frame", x.frame);
    u("conversation", x.conv);
    text("file", x.file);
    j.key("message");
    put_str(o, top::ascii_text(x.message));
    j.close_object();
  }
  j.close_array();
}

}  // namespace

void write_json(std::string& out, const Report& r) {
  Doc j(out, 2);
  Writer w{j, j.out(), r, *r.data, *r.stats};
  j.open_object();
  w.overview();
  w.angles();
  w.rates();
  w.latency();
  w.streams();
  w.findings();
  w.unanswered();
  j.close_object();
  j.out() += '\n';
}

}  // namespace topdump::report
