// topdump report --json: the analysis of report.hpp as one JSON document,
// through the one JSON writer (json_writer.hpp). Keys: docs/REPORT.md.
#include <cmath>

#include "output/json_writer.hpp"
#include "report/report.hpp"
#include "top/detail/text.hpp"

namespace topdump::report {

using namespace jsonw;

namespace {

// A measure rounded to 1e-4.
void put_measure(std::string& o, double v) { put_double(o, std::round(v * 1e4) / 1e4); }

// The document's writer: the value helpers and one function per section.
struct Writer {
  Doc& j;
  std::string& o;
  const Report& r;
  const ReportSink& d;
  const Stats& s;

  void num(std::string_view k, double v, bool measured = true) {  // null when not measured
    j.key(k);
    put_or_null(o, measured, [&] { put_measure(o, v); });
  }
  void opt(std::string_view k, double v) { num(k, v, v >= 0); }  // negative: not measured
  void esc(std::string_view k, std::string_view bytes) {
    j.key(k);
    put_esc(o, bytes);
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
  j.u("frames", s.frames);
  j.time("first_time", s.first);
  j.time("last_time", s.last);
  j.str("worst", top::to_string(r.worst));
  j.str("model", top::to_string(r.model));
  num("tolerance_deg", r.opts.tolerance_deg);
  j.key_objects("conversations", s.conversations, [&](const ConvStats& c) {
    conversation_members(j, c);
    j.str("dialect", top::to_string(dialect_of(r, c)));
    j.str("model", model_text(r, c));
    j.u("frames", c.frames);
  });
  j.key_objects("what_went_wrong", r.facts, [&](const Fact& f) {
    j.str("severity", top::to_string(f.severity));
    j.key("code");
    put_or_null(o, f.code.has_value(), [&] { put_str(o, top::to_string(*f.code)); });
    j.str("text", f.text);
    j.str("section", f.anchor);
    if (f.code) {
      j.str("evidence", top::evidence(*f.code));
      j.str("remedy", top::remedy(*f.code));
      j.key("frame");
      put_nonzero(o, f.frame);
      j.u("count", f.count);
    }
  });
  j.close_object();
}

void Writer::angles() {
  j.key_objects("angle_commands", r.angles, [&](const AngleResult& a) {
    j.u("conversation", a.conv);
    j.u("frame", a.cmd->frame);
    j.time("time", a.cmd->t);
    j.str("ident", a.cmd->ident);
    j.str("axis", axis_name(a.cmd->axis));
    j.u("commands", a.cmd->commands);
    num("target_deg", a.cmd->target);
    num("speed_deg_s", a.cmd->speed, a.cmd->speed > 0);
    j.str("attitude", a.attitude);
    j.u("samples", a.samples);
    num("start_deg", a.start);
    num("effective_target_deg", a.effective);
    opt("expected_s", a.expected_s);
    opt("settling_s", a.settling_s);
    num("overshoot_deg", a.overshoot_deg);
    num("overshoot_pct", a.overshoot_pct);
    num("steady_state_error_deg", a.final_error);
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
  });
}

void Writer::rates() {
  j.key_object("rate_commands");
  j.key("refresh_limit_ms");
  put_or_null(o, r.refresh_limit_ms != 0, [&] { put_i(o, r.refresh_limit_ms); });
  j.str("refresh_evidence", r.refresh_evidence);
  j.str("scale_verdict", to_string(r.scale_verdict));
  opt("measured_deg_s_per_step", r.scale_runs ? r.scale_measured : -1);
  j.u("scale_runs", r.scale_runs);
  j.u("scale_other_way_runs", r.scale_other_way);
  j.key_objects("runs", r.runs, [&](const RateRun& x) {
    j.u("conversation", x.conv);
    j.u("frame", x.first_frame);
    j.str("ident", x.ident);
    j.str("axis", axis_name(x.axis));
    j.time("start", x.start);
    j.time("end", x.end);
    j.u("commands", x.commands);
    j.key("steps");
    put_i(o, x.steps);
    num("commanded_deg_s", x.commanded);
    num("catalog_deg_s_per_step", x.scale);
    num("median_refresh_ms", x.median_interval_ms);
    num("max_refresh_ms", x.max_interval_ms);
    j.u("samples", x.samples);
    num("measured_deg_s", x.measured, x.measured_ok);
    num("measured_deg_s_per_step", x.per_step, x.measured_ok);
  });
  j.key_objects("refresh_gaps", r.gaps, [&](const RefreshGap& g) {
    j.u("conversation", g.conv);
    j.u("frame", g.frame);
    j.str("ident", g.ident);
    j.time("time", g.t);
    num("gap_ms", g.gap_ms);
  });
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
        num("from_ms", latency_bin_ms(b));
        j.u("count", it->second[b]);
        j.close_object();
      }
    j.close_array();
    j.close_object();
  }
  std::vector<Slow> slow = d.slowest;
  std::sort(slow.begin(), slow.end(),
            [](const Slow& a, const Slow& b) { return a.latency_us > b.latency_us; });
  j.key_objects("slowest", slow, [&](const Slow& x) {
    j.str("ident", x.ident);
    num("latency_ms", static_cast<double>(x.latency_us) / 1000.0);
    j.u("request", x.request);
    j.u("response", x.response);
    j.u("conversation", x.conv);
    j.time("time", x.ts);
    esc("response_raw", x.response_raw);
  });
  j.close_object();
}

void Writer::streams() {
  j.key_objects("streams", r.streams, [&](const StreamResult& x) {
    j.u("conversation", x.conv);
    stream_members(j, x.stat, StreamKeys{.asked_by = true, .measured_per_hz = 1e4});
    j.key("bucket_s");
    put_double(o, static_cast<double>(x.bucket_us) / 1e6);
    j.key_array("rate_hz");
    for (float v : x.rate) {
      j.item();
      put_measure(o, v);
    }
    j.close_array();
    j.u("gap_count", x.gap_count);
    j.key_objects("gaps", x.gaps, [&](const auto& g) {
      j.time("time", g.t);
      num("ms", g.ms);
    });
  });
}

void Writer::findings() {
  j.key_array("findings");
  for (const auto& [code, c] : d.codes) {
    j.item_object();
    j.str("code", code);
    j.str("severity", top::to_string(c.severity));
    j.u("count", c.count);
    j.time("first", c.first);
    j.time("last", c.last);
    counts_member(j, "senders", c.senders);
    j.key_objects("examples", c.examples, [&](const Example& x) {
      j.str("file", x.file);
      j.u("frame", x.frame);
      j.time("time", x.ts);
      j.u("record", x.record);
      j.u("record_offset", x.offset);
      j.u("finding_offset", x.at);
      j.str("from", x.from);
      j.str("to", x.to);
      esc("raw", x.raw);
      j.str("decoded", top::ascii_text(x.decoded));
      j.str("message", top::ascii_text(x.message));
    });
    j.close_object();
  }
  j.close_array();
}

void Writer::unanswered() {
  j.key_objects("unanswered", d.unanswered, [&](const Unanswered& x) {
    j.time("time", x.ts);
    j.u("frame", x.frame);
    j.u("conversation", x.conv);
    j.str("file", x.file);
    j.str("message", top::ascii_text(x.message));
  });
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
