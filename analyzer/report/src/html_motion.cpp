// topdump report, the HTML page: the motion plots and the response to commands.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "capture/sources.hpp"
#include "html_page.hpp"
#include "report/analysis.hpp"
#include "report/report.hpp"
#include "svg.hpp"
#include "top/detail/text.hpp"

namespace topdump::report::html {

void Page::motion() {
  o += "<section id=\"motion\"><h2>2. Gimbal motion</h2>";
  o += "<p class=\"muted\">Per conversation and axis, up and right positive: the reported attitude "
       "(GAC, GIC or GIA replies and "
       "pushes, solid), the commanded angle (dashed, held until the next command), angle "
       "commands (diamonds at their target), rate commands (triangles above the plot: up "
       "positive, down negative, circle zero) and other gimbal commands (dotted lines). Hover a "
       "mark for its frame.</p>";
  bool any = false;
  for (const auto& [id, c] : r.data->convs) {
    if (c.attitude.empty() && c.angles.empty() && c.rates.empty() && c.marks.empty()) continue;
    any = true;
    o += "<h3>Conversation " + std::to_string(id) + ": <code>" + markup_escape(c.a) +
         "</code> and <code>" + markup_escape(c.b) + "</code> (" +
         markup_escape(std::string(top::to_string(c.dialect))) + ")</h3>";
    for (int axis = 0; axis < kAxes; ++axis) {
      svg::TimePlot p;
      p.width = kWidth;
      p.height = 210;
      p.t0 = t0;
      p.t1 = t1;
      p.title = std::string(axis_name(axis));
      p.unit = "deg";
      bool has_motion = false;
      for (const auto& [ident, a] : c.attitude) {
        svg::Series s;
        s.label = ident + " " + axis_name(axis);
        // the earth frame's attitude (Topotek GIC, GIA) in its own colour
        s.color =
            a.spec && a.spec->reference == top::Reference::earth ? "#9467bd" : kAxisColor[axis];
        s.t = a.t;
        s.v = a.v[static_cast<std::size_t>(axis)];
        s.break_us = 2'000'000;
        const auto mm = std::minmax_element(s.v.begin(), s.v.end());
        if (mm.first != s.v.end() && *mm.second - *mm.first > 0.005f) has_motion = true;
        p.series.push_back(std::move(s));
      }
      svg::Series cmd;
      cmd.label = "commanded";
      cmd.color = kCmdColor[axis];
      cmd.step = true;
      cmd.dashed = true;
      // One mark per three pixel columns and shape: the first, with a count
      // (the title of each is only built for the ones drawn).
      // (commands come in time order: the last column of each shape is enough)
      std::map<char, std::pair<long, std::size_t>> last;
      auto mark = [&](std::int64_t t, char shape, auto make) {
        const long col = svg::column(p, t) / 3;  // a mark is about 8 px wide
        auto [it, fresh] = last.try_emplace(shape, col, p.markers.size());
        if (!fresh && it->second.first == col) {
          ++p.markers[it->second.second].count;
          return;
        }
        it->second = {col, p.markers.size()};
        p.markers.push_back(make());
      };
      std::string_view signed_for;  // the identifier `sign` is for (the same all along, mostly)
      int sign = 1;
      for (const auto& a : c.angles) {
        if (a.axis != axis) continue;
        // up and right positive, as the attitude: the target the response
        // analysis compares (a Topotek pitch of 30 on the wire is 30 down)
        if (a.ident != signed_for) {
          bool ambiguous = false;
          sign = command_sign(c.dialect, a.ident, axis, series_for(c, a.ident, axis), r.model,
                              ambiguous);
          signed_for = a.ident;
        }
        const float up = sign < 0 ? -a.target : a.target;
        cmd.t.push_back(a.t);
        cmd.v.push_back(up);
        mark(a.t, 'd', [&] {
          return svg::Marker{a.t,
                             up,
                             false,
                             'd',
                             kCmdColor[axis],
                             std::string(a.ident) + " " + fmt("%.2f", a.target) + " deg" +
                                 (up != a.target ? " (" + fmt("%.2f", up) + " as plotted)" : "") +
                                 ", speed " + fmt("%.1f", a.speed) + " deg/s (frame " +
                                 std::to_string(a.frame) + ", " + clock_text(a.t) + ")"};
        });
      }
      for (const auto& x : c.rates) {
        if (x.axis != axis) continue;
        const char shape = x.steps > 0 ? '^' : x.steps < 0 ? 'v' : 'o';
        mark(x.t, shape, [&] {
          return svg::Marker{x.t,
                             0,
                             true,
                             shape,
                             kCmdColor[axis],
                             std::string(x.ident) + " " + std::to_string(x.steps) + " steps (" +
                                 fmt("%.1f", x.rate) + " deg/s by the catalog, frame " +
                                 std::to_string(x.frame) + ", " + clock_text(x.t) + ")"};
        });
      }
      for (const auto& m : c.marks)
        mark(m.t, '|', [&] {
          return svg::Marker{m.t,
                             0,
                             false,
                             '|',
                             "#777",
                             std::string(m.ident) + " " + std::string(m.what) + " (frame " +
                                 std::to_string(m.frame) + ", " + clock_text(m.t) + ")"};
        });
      const bool has_cmd =
          !cmd.t.empty() || std::any_of(c.rates.begin(), c.rates.end(),
                                        [&](const RateCommand& x) { return x.axis == axis; });
      if (!has_cmd && !has_motion && axis != 0) continue;  // yaw always: even a still gimbal
      if (!cmd.t.empty()) p.series.push_back(std::move(cmd));
      svg::time_plot(o, p);
    }
  }
  if (!any) o += "<p class=\"muted\">No gimbal command and no attitude in the capture.</p>";
  o += "</section>";
}

void Page::response() {
  o += "<section id=\"response\"><h2>3. Response analysis</h2>";
  o += "<p>Angle commands: settling time is when the attitude came within " +
       fmt("%g", r.opts.tolerance_deg) +
       " deg of the target (clamped to the model's range) and stayed there until the next "
       "command on the axis (<code>--tolerance</code>); expected is the step over the "
       "commanded speed. A target sent again (the same command, target and speed, nothing "
       "else on the axis between) is one row, judged from its first frame: commands counts "
       "them.</p>";
  if (r.angles.empty()) {
    o += "<p class=\"muted\">No angle command.</p>";
  } else {
    o += "<table><tr><th>frame</th><th>time</th><th>conv</th><th>command</th><th>axis</th>"
         "<th>commands</th><th>target</th><th>from</th><th>speed</th>"
         "<th>expected</th><th>settling</th><th>overshoot</th><th>steady-state "
         "error</th><th>flags</th></tr>";
    for (std::size_t i = 0; i < r.angles.size() && i < kMaxRows; ++i) {
      const AngleResult& a = r.angles[i];
      std::string flags;
      auto flag = [&](bool on, const std::string& t, bool info = false) {
        if (on)
          flags += "<span class=\"flag" + std::string(info ? " info" : "") + "\">" + t + "</span>";
      };
      flag(a.no_attitude, "no attitude", true);
      flag(a.never_reached, "never reached");
      flag(a.other_way, "moved the other way (sign inverted" +
                            (a.mirrored_settling_s >= 0
                                 ? ", at -target after " + fmt("%.3f", a.mirrored_settling_s) + " s"
                                 : std::string()) +
                            ")");
      flag(a.out_of_range, "outside the range " + fmt("%g", a.cmd->min) + ".." +
                               fmt("%g", a.cmd->max) + ": clamped");
      flag(a.superseded, "superseded", true);
      flag(a.still_moving, "still on its way at the capture's end", true);
      o += "<tr>" + tdn(frame_ref(a.cmd->frame)) + td(clock_text(a.cmd->t)) +
           tdn(std::to_string(a.conv)) + td(std::string(a.cmd->ident)) +
           td(axis_name(a.cmd->axis)) + tdn(std::to_string(a.cmd->commands)) +
           tdn(fmt("%.2f", a.cmd->target)) + tdn(a.no_attitude ? "-" : fmt("%.2f", a.start)) +
           tdn(a.cmd->speed > 0 ? fmt("%.1f", a.cmd->speed) : "-") +
           tdn(a.expected_s >= 0 ? fmt("%.3f s", a.expected_s) : "-") +
           tdn(a.settling_s >= 0 ? fmt("%.3f s", a.settling_s) : "-") +
           tdn(a.no_attitude ? "-" : fmt("%.2f deg", a.overshoot_deg)) +
           tdn(a.no_attitude ? "-" : fmt("%.2f deg", a.final_error)) + td(flags) + "</tr>";
    }
    o += "</table>" + more_rows(r.angles.size());
  }
  o += "<h3 id=\"rates\">Rate commands</h3>";
  if (r.runs.empty()) {
    o += "<p class=\"muted\">No rate command.</p>";
  } else {
    o += "<p>Runs of rate commands (one axis, one value, each refreshed within the limit). "
         "Measured rate: least squares over the attitude during the run.";
    if (r.refresh_limit_ms)
      o += " Refresh limit " + std::to_string(r.refresh_limit_ms) +
           " ms (field: " + markup_escape(r.refresh_evidence) + ").";
    o += "</p>";
    if (r.scale_verdict != ScaleVerdict::none) {
      o += "<p><b>Speed unit:</b> the gimbal moved " + fmt("%.3f", r.scale_measured) +
           " deg/s per step (median of " + std::to_string(r.scale_runs) + " run" +
           (r.scale_runs == 1 ? "" : "s") + "). ";
      o += r.scale_verdict == ScaleVerdict::field
               ? "The capture supports the field's 0.5 deg/s per step, not the document's 0.1."
           : r.scale_verdict == ScaleVerdict::document
               ? "The capture supports the document's 0.1 deg/s per step, not the field's 0.5."
               : "The capture supports neither 0.1 (document) nor 0.5 (field) deg/s per step.";
      o += "</p>";
    }
    o += "<table><tr><th>frame</th><th>start</th><th>conv</th><th>command</th><th>axis</th>"
         "<th>commands</th><th>steps</th><th>commanded</th><th>refresh median / max</th>"
         "<th>measured</th><th>per step</th></tr>";
    for (std::size_t i = 0; i < r.runs.size() && i < kMaxRows; ++i) {
      const RateRun& x = r.runs[i];
      o += "<tr>" + tdn(frame_ref(x.first_frame)) + td(clock_text(x.start)) +
           tdn(std::to_string(x.conv)) + td(x.ident) + td(axis_name(x.axis)) +
           tdn(std::to_string(x.commands)) + tdn(std::to_string(x.steps)) +
           tdn(fmt("%.1f deg/s", x.commanded)) +
           tdn(x.commands > 1
                   ? fmt("%.0f", x.median_interval_ms) + " / " + fmt("%.0f ms", x.max_interval_ms)
                   : "-") +
           tdn(x.measured_ok ? fmt("%.2f deg/s", x.measured) : "-") +
           tdn(x.measured_ok ? fmt("%.3f", x.per_step) : "-") + "</tr>";
    }
    o += "</table>" + more_rows(r.runs.size());
    if (!r.gaps.empty()) {
      o += "<h3>Refresh gaps</h3><p>Rate commands not followed by another on the axis within " +
           std::to_string(r.refresh_limit_ms) +
           " ms: the motors stop.</p><table><tr><th>frame"
           "</th><th>time</th><th>conv</th><th>command</th><th>gap</th></tr>";
      for (std::size_t i = 0; i < r.gaps.size() && i < kMaxRows; ++i) {
        const RefreshGap& g = r.gaps[i];
        o += "<tr>" + tdn(frame_ref(g.frame)) + td(clock_text(g.t)) + tdn(std::to_string(g.conv)) +
             td(g.ident) + tdn(fmt("%.0f ms", g.gap_ms)) + "</tr>";
      }
      o += "</table>" + more_rows(r.gaps.size());
    }
  }
  o += "</section>";
}

}  // namespace topdump::report::html
