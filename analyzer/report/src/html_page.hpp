// The HTML page of a report (the report room's own header): the page and
// its helpers, whose sections live in html.cpp, html_motion.cpp and
// html_timing.cpp.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "report/report.hpp"
#include "top/detail/text.hpp"

namespace topdump::report::html {

using top::markup_escape;

inline constexpr std::size_t kMaxRows = 300;  // table rows per table (the JSON has all)
inline constexpr int kWidth = 960;
inline constexpr const char* kAxisColor[kAxes] = {"#1f77b4", "#d62728", "#2ca02c"};
inline constexpr const char* kCmdColor[kAxes] = {"#0b3c66", "#7a1010", "#145214"};

inline std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

inline std::string sev_span(top::Severity s) {
  const std::string n(top::to_string(s));
  return "<span class=\"sev-" + n + "\">" + n + "</span>";
}

inline std::string td(const std::string& s) { return "<td>" + s + "</td>"; }
inline std::string tdn(const std::string& s) { return "<td class=\"n\">" + s + "</td>"; }
inline std::string frame_ref(std::uint64_t n) { return n ? "#" + std::to_string(n) : "-"; }

inline std::string more_rows(std::size_t total) {
  return total > kMaxRows ? "<p class=\"muted\">" + std::to_string(total - kMaxRows) +
                                " more rows in <code>topdump report --json</code>.</p>"
                          : "";
}

struct Page {
  const Report& r;
  std::string& o;
  std::int64_t t0 = 0, t1 = 0;  // the time axis of every plot

  void overview();
  void motion();
  void response();
  void latency();
  void streams();
  void findings();
  void unanswered();

  // Opens section `id` under heading `title`. With nothing to show
  // (`empty`), writes `none` (a muted or ok paragraph), closes the section
  // and returns false.
  bool open(std::string_view id, std::string_view title, bool empty, std::string_view none) {
    o += "<section id=\"";
    o += id;
    o += "\"><h2>";
    o += title;
    o += "</h2>";
    if (!empty) return true;
    o += none;
    o += "</section>";
    return false;
  }
};

}  // namespace topdump::report::html
