// Inline SVG plots of topdump report: time series decimated to min/max per
// pixel column (so a plot's size does not grow with the capture), step
// lines, markers with tooltips, bar charts. Output is well-formed XML
// (escaped text, quoted attributes, closed elements).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "report/report.hpp"

namespace topdump::report::svg {

struct Series {
  std::string label, color;
  std::vector<std::int64_t> t;  // microseconds
  std::vector<float> v;
  bool step = false;  // held until the next point (a commanded value)
  bool dashed = false;
  std::int64_t break_us = 0;  // no line across a gap longer than this (0: never)
};

struct Marker {
  std::int64_t t = 0;
  double v = 0;      // plotted at this value (ignored when `top`)
  bool top = false;  // on the band above the plot instead
  char shape = 'o';  // 'o' circle, '^' up, 'v' down, 'd' diamond, '|' vertical line
  std::string color, title;
  int count = 1;  // marks merged into this one
};

struct TimePlot {
  int width = 900, height = 200;
  std::int64_t t0 = 0, t1 = 0;  // the time axis
  std::string title, unit;
  std::vector<Series> series;
  std::vector<Marker> markers;
  // Reference lines (asked rate): value and label.
  std::vector<std::pair<double, std::string>> hlines;
};

// The pixel column of time `t` in the plot (markers in one column and of
// one shape are drawn as one).
long column(const TimePlot& p, std::int64_t t);

// Appends <svg>...</svg>. Markers beyond one per pixel column and shape are
// merged (the title says how many).
void time_plot(std::string& out, const TimePlot& p);

// A bar chart with a label under each bar (latency histograms).
void bars(std::string& out, const std::vector<std::string>& labels,
          const std::vector<std::uint64_t>& counts, const std::string& color, int width,
          int height);

// Rows of event counts per pixel column (the findings timeline).
struct Lane {
  std::string label, color;
  const TimeHist* counts = nullptr;  // events over time
};
void lanes(std::string& out, const std::vector<Lane>& lanes, std::int64_t t0, std::int64_t t1,
           int width);

}  // namespace topdump::report::svg
