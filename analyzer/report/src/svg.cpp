// Inline SVG plots of topdump report (report_svg.hpp).
#include "svg.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "top/detail/text.hpp"

namespace topdump::report::svg {

using top::markup_escape;

namespace {

constexpr int kLeft = 58, kRight = 12, kTop = 22, kBottom = 26;

// One decimal, as printf's "%.1f" but for ties (rounded away from zero
// here) and with no "-0.0": a plot writes hundreds of thousands of these,
// and to_chars with a precision costs a printf each.
void put_num(std::string& o, double v) {
  if (!(std::fabs(v) < 1e15)) {  // NaN, infinities, huge: never a coordinate
    char b[64];
    const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, 1);
    o.append(b, r.ec == std::errc() ? r.ptr : b);
    return;
  }
  const long long t = std::llround(v * 10);
  unsigned long long u =
      t < 0 ? 0ULL - static_cast<unsigned long long>(t) : static_cast<unsigned long long>(t);
  char b[24];
  char* p = b + sizeof b;
  *--p = static_cast<char>('0' + u % 10);
  *--p = '.';
  u /= 10;
  do {
    *--p = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u);
  if (t < 0) *--p = '-';
  o.append(p, static_cast<std::size_t>(b + sizeof b - p));
}
std::string num(double v) {
  std::string s;
  put_num(s, v);
  return s;
}

// A "nice" tick step covering `span` in about `n` steps.
double nice_step(double span, int n) {
  if (span <= 0) return 1;
  const double raw = span / n, mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * mag) return m * mag;
  return 10 * mag;
}

std::string tick_text(double v, double step) {
  char b[32];
  if (std::fabs(v) < step * 1e-6) v = 0;  // no "-0"
  const int dec = step >= 1 ? 0 : step >= 0.1 ? 1 : step >= 0.01 ? 2 : 3;
  std::snprintf(b, sizeof b, "%.*f", dec, v);
  return b;
}

struct Frame {
  int w, h;
  double x0, x1, y0, y1;
  double px(double x) const { return kLeft + (x - x0) / (x1 - x0) * (w - kLeft - kRight); }
  double py(double y) const { return kTop + (y1 - y) / (y1 - y0) * (h - kTop - kBottom); }
};

void axes(std::string& o, const Frame& f, const std::string& title, const std::string& unit,
          const std::string& xunit) {
  o += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(kTop) + "\" width=\"" +
       num(f.w - kLeft - kRight) + "\" height=\"" + num(f.h - kTop - kBottom) +
       "\" class=\"plotbg\"/>";
  const double ys = nice_step(f.y1 - f.y0, 4);
  for (double y = std::ceil(f.y0 / ys) * ys; y <= f.y1 + ys * 1e-9; y += ys) {
    const std::string py = num(f.py(y));
    o += "<line x1=\"" + num(kLeft) + "\" x2=\"" + num(f.w - kRight) + "\" y1=\"" + py +
         "\" y2=\"" + py + "\" class=\"grid\"/>";
    o += "<text x=\"" + num(kLeft - 4) + "\" y=\"" + num(f.py(y) + 4) +
         "\" class=\"tick\" text-anchor=\"end\">" + tick_text(y, ys) + "</text>";
  }
  const double xs = nice_step(f.x1 - f.x0, 8);
  for (double x = std::ceil(f.x0 / xs) * xs; x <= f.x1 + xs * 1e-9; x += xs) {
    const std::string px = num(f.px(x));
    o += "<line x1=\"" + px + "\" x2=\"" + px + "\" y1=\"" + num(kTop) + "\" y2=\"" +
         num(f.h - kBottom) + "\" class=\"grid\"/>";
    o += "<text x=\"" + px + "\" y=\"" + num(f.h - kBottom + 14) +
         "\" class=\"tick\" text-anchor=\"middle\">" + tick_text(x, xs) + "</text>";
  }
  o += "<text x=\"" + num(f.w - kRight) + "\" y=\"" + num(f.h - 2) +
       "\" class=\"tick\" text-anchor=\"end\">" + markup_escape(xunit) + "</text>";
  o += "<text x=\"4\" y=\"14\" class=\"ptitle\">" + markup_escape(title) +
       (unit.empty() ? "" : " (" + markup_escape(unit) + ")") + "</text>";
}

// Decimates a series to at most two points per pixel column (its min and
// max, in the order they came), breaking the line across long gaps.
void polyline(std::string& o, const Frame& f, const Series& s) {
  const std::size_t n = std::min(s.t.size(), s.v.size());
  if (n == 0) return;
  const double cols = f.w - kLeft - kRight;
  std::vector<std::string> parts;
  std::string pts;
  long col = -1;
  float lo = 0, hi = 0;
  std::size_t lo_i = 0, hi_i = 0;
  double last_y = 0;
  auto x_of = [&](std::int64_t t) { return (static_cast<double>(t) / 1e6 - f.x0) / (f.x1 - f.x0); };
  auto point = [&](double x, double y) {
    put_num(pts, x);
    pts += ',';
    put_num(pts, f.py(y));
    pts += ' ';
  };
  auto flush = [&]() {
    if (col < 0) return;
    const double x = kLeft + static_cast<double>(col) + 0.5;
    if (lo_i <= hi_i) {
      point(x, lo);
      if (hi != lo) point(x, hi);
    } else {
      point(x, hi);
      point(x, lo);
    }
    last_y = s.v[std::max(lo_i, hi_i)];
  };
  auto end_line = [&]() {
    if (pts.size() > 0) parts.push_back(std::move(pts));
    pts.clear();
  };
  for (std::size_t i = 0; i < n; ++i) {
    const long c =
        std::clamp(static_cast<long>(x_of(s.t[i]) * cols), 0L, static_cast<long>(cols) - 1);
    const bool brk = s.break_us > 0 && i > 0 && s.t[i] - s.t[i - 1] > s.break_us;
    if (c != col || brk) {
      flush();
      if (brk) {
        if (s.step) point(f.px(static_cast<double>(s.t[i]) / 1e6), last_y);
        end_line();
      } else if (s.step && col >= 0) {
        // hold the previous value up to this point
        point(kLeft + static_cast<double>(c) + 0.5, last_y);
      }
      col = c;
      lo = hi = s.v[i];
      lo_i = hi_i = i;
    } else {
      if (s.v[i] < lo) lo = s.v[i], lo_i = i;
      if (s.v[i] > hi) hi = s.v[i], hi_i = i;
    }
  }
  flush();
  if (s.step) point(f.w - kRight, last_y);
  end_line();
  for (const auto& p : parts) {
    o += "<polyline fill=\"none\" stroke=\"" + s.color + "\" stroke-width=\"1.5\"" +
         (s.dashed ? " stroke-dasharray=\"5,3\"" : "") + " points=\"" + p + "\"><title>" +
         markup_escape(s.label) + "</title></polyline>";
  }
}

void marker(std::string& o, double x, double y, const Marker& m, int count) {
  const std::string title = "<title>" + markup_escape(m.title) +
                            (count > 1 ? " (+" + std::to_string(count - 1) + " more)" : "") +
                            "</title>";
  const std::string fill = " fill=\"" + m.color + "\" stroke=\"#222\" stroke-width=\"0.5\"";
  switch (m.shape) {
    case '^':
      o += "<path d=\"M" + num(x) + " " + num(y - 5) + " L" + num(x - 4) + " " + num(y + 3) + " L" +
           num(x + 4) + " " + num(y + 3) + " Z\"" + fill + ">" + title + "</path>";
      break;
    case 'v':
      o += "<path d=\"M" + num(x) + " " + num(y + 5) + " L" + num(x - 4) + " " + num(y - 3) + " L" +
           num(x + 4) + " " + num(y - 3) + " Z\"" + fill + ">" + title + "</path>";
      break;
    case 'd':
      o += "<path d=\"M" + num(x) + " " + num(y - 5) + " L" + num(x + 5) + " " + num(y) + " L" +
           num(x) + " " + num(y + 5) + " L" + num(x - 5) + " " + num(y) + " Z\"" + fill + ">" +
           title + "</path>";
      break;
    default:
      o += "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"3.5\"" + fill + ">" + title +
           "</circle>";
  }
}

}  // namespace

long column(const TimePlot& p, std::int64_t t) {
  const double span = std::max<double>(1, static_cast<double>(p.t1 - p.t0));
  return static_cast<long>(static_cast<double>(t - p.t0) / span * (p.width - kLeft - kRight));
}

void time_plot(std::string& o, const TimePlot& p) {
  Frame f{p.width, p.height, 0, static_cast<double>(p.t1 - p.t0) / 1e6, 0, 1};
  if (f.x1 <= 0) f.x1 = 1;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& s : p.series)
    for (float v : s.v)
      lo = std::min(lo, static_cast<double>(v)), hi = std::max(hi, static_cast<double>(v));
  for (const auto& m : p.markers)
    if (!m.top && m.shape != '|') lo = std::min(lo, m.v), hi = std::max(hi, m.v);
  for (const auto& h : p.hlines) lo = std::min(lo, h.first), hi = std::max(hi, h.first);
  if (!std::isfinite(lo)) lo = -1, hi = 1;
  if (hi - lo < 1) {
    const double mid = (hi + lo) / 2;
    lo = mid - 0.5, hi = mid + 0.5;
  }
  const double pad = (hi - lo) * 0.08;
  f.y0 = lo - pad;
  f.y1 = hi + pad;
  o += "<svg width=\"" + std::to_string(p.width) + "\" height=\"" + std::to_string(p.height) +
       "\" viewBox=\"0 0 " + std::to_string(p.width) + " " + std::to_string(p.height) +
       "\" class=\"plot\">";
  axes(o, f, p.title, p.unit, "s from the first frame");
  for (const auto& h : p.hlines) {
    const std::string y = num(f.py(h.first));
    o += "<line x1=\"" + num(kLeft) + "\" x2=\"" + num(p.width - kRight) + "\" y1=\"" + y +
         "\" y2=\"" + y + "\" class=\"ref\"><title>" + markup_escape(h.second) + "</title></line>";
  }
  // shift the series to the plot's origin
  for (const auto& s : p.series) {
    Series shifted = s;
    for (auto& t : shifted.t) t -= p.t0;
    polyline(o, f, shifted);
  }
  // markers: one per pixel column and shape
  std::map<std::pair<long, char>, std::pair<const Marker*, int>> seen;
  for (const auto& m : p.markers) {
    const double x = f.px(static_cast<double>(m.t - p.t0) / 1e6);
    auto& e = seen[{static_cast<long>(x - kLeft), m.shape}];
    if (!e.first) e.first = &m;
    e.second += m.count;
  }
  for (const auto& [k, e] : seen) {
    const Marker& m = *e.first;
    const double x = f.px(static_cast<double>(m.t - p.t0) / 1e6);
    if (m.shape == '|') {
      o += "<line x1=\"" + num(x) + "\" x2=\"" + num(x) + "\" y1=\"" + num(kTop) + "\" y2=\"" +
           num(p.height - kBottom) + "\" stroke=\"" + m.color +
           "\" stroke-width=\"1\" stroke-dasharray=\"2,2\"><title>" + markup_escape(m.title) +
           (e.second > 1 ? " (+" + std::to_string(e.second - 1) + " more)" : "") +
           "</title></line>";
      continue;
    }
    marker(o, x, m.top ? kTop - 8 : f.py(m.v), m, e.second);
  }
  // legend
  double lx = p.width - kRight;
  for (auto it = p.series.rbegin(); it != p.series.rend(); ++it) {
    lx -= 8.0 + 6.5 * static_cast<double>(it->label.size()) + 18;
    o += "<line x1=\"" + num(lx) + "\" x2=\"" + num(lx + 14) + "\" y1=\"10\" y2=\"10\" stroke=\"" +
         it->color + "\" stroke-width=\"2\"" + (it->dashed ? " stroke-dasharray=\"4,2\"" : "") +
         "/><text x=\"" + num(lx + 18) + "\" y=\"14\" class=\"tick\">" + markup_escape(it->label) +
         "</text>";
  }
  o += "</svg>";
}

void bars(std::string& o, const std::vector<std::string>& labels,
          const std::vector<std::uint64_t>& counts, const std::string& color, int width,
          int height) {
  const std::uint64_t top =
      counts.empty() ? 1
                     : std::max<std::uint64_t>(1, *std::max_element(counts.begin(), counts.end()));
  o += "<svg width=\"" + std::to_string(width) + "\" height=\"" + std::to_string(height) +
       "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
       "\" class=\"plot\">";
  const double n = static_cast<double>(std::max<std::size_t>(1, counts.size()));
  const double bw = (width - 20) / n, base = height - 18;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double h = (base - 14) * static_cast<double>(counts[i]) / static_cast<double>(top);
    const double x = 10 + bw * static_cast<double>(i);
    o += "<rect x=\"" + num(x + 1) + "\" y=\"" + num(base - h) + "\" width=\"" +
         num(std::max(1.0, bw - 2)) + "\" height=\"" + num(h) + "\" fill=\"" + color +
         "\"><title>" + markup_escape(labels[i]) + ": " + std::to_string(counts[i]) +
         "</title></rect>";
    if (counts.size() <= 12 || i % 2 == 0)
      o += "<text x=\"" + num(x + bw / 2) + "\" y=\"" + num(height - 4) +
           "\" class=\"tick\" text-anchor=\"middle\">" + markup_escape(labels[i]) + "</text>";
    if (counts[i])
      o += "<text x=\"" + num(x + bw / 2) + "\" y=\"" + num(base - h - 3) +
           "\" class=\"tick\" text-anchor=\"middle\">" + std::to_string(counts[i]) + "</text>";
  }
  o += "</svg>";
}

void lanes(std::string& o, const std::vector<Lane>& ls, std::int64_t t0, std::int64_t t1,
           int width) {
  const int row = 22, height = row * static_cast<int>(ls.size()) + kBottom + 4;
  const double cols = width - kLeft - kRight;
  const double span = std::max<double>(1, static_cast<double>(t1 - t0));
  o += "<svg width=\"" + std::to_string(width) + "\" height=\"" + std::to_string(height) +
       "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
       "\" class=\"plot\">";
  Frame f{width, height, 0, span / 1e6, 0, 1};
  const double xs = nice_step(f.x1, 8);
  for (double x = 0; x <= f.x1 + xs * 1e-9; x += xs) {
    const std::string px = num(f.px(x));
    o += "<line x1=\"" + px + "\" x2=\"" + px + "\" y1=\"2\" y2=\"" + num(height - kBottom) +
         "\" class=\"grid\"/><text x=\"" + px + "\" y=\"" + num(height - kBottom + 14) +
         "\" class=\"tick\" text-anchor=\"middle\">" + tick_text(x, xs) + "</text>";
  }
  for (std::size_t r = 0; r < ls.size(); ++r) {
    const double y = 4 + row * static_cast<double>(r);
    o += "<text x=\"" + num(kLeft - 4) + "\" y=\"" + num(y + 14) +
         "\" class=\"tick\" text-anchor=\"end\">" + markup_escape(ls[r].label) + "</text>";
    std::vector<std::uint32_t> per(static_cast<std::size_t>(cols), 0);
    const TimeHist& th = *ls[r].counts;
    for (std::size_t b = 0; b < th.counts().size(); ++b) {
      if (!th.counts()[b]) continue;
      const std::int64_t t = th.origin() + static_cast<std::int64_t>(b) * th.width();
      const auto c = static_cast<std::size_t>(
          std::clamp((static_cast<double>(t - t0) / span) * cols, 0.0, cols - 1));
      per[c] += th.counts()[b];
    }
    const std::uint32_t top = std::max<std::uint32_t>(1, *std::max_element(per.begin(), per.end()));
    for (std::size_t c = 0; c < per.size(); ++c) {
      if (!per[c]) continue;
      // height grows with the log of the count so single events stay visible
      const double h = 4 + 14 * std::log1p(per[c]) / std::log1p(top);
      o += "<rect x=\"" + num(kLeft + static_cast<double>(c)) + "\" y=\"" + num(y + 18 - h) +
           "\" width=\"1.6\" height=\"" + num(h) + "\" fill=\"" + ls[r].color + "\"><title>" +
           std::to_string(per[c]) + " " + markup_escape(ls[r].label) + "</title></rect>";
    }
  }
  o += "<text x=\"" + num(width - kRight) + "\" y=\"" + num(height - 2) +
       "\" class=\"tick\" text-anchor=\"end\">s from the first frame</text>";
  o += "</svg>";
}

}  // namespace topdump::report::svg
