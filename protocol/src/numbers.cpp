#include "numbers.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace top::detail {

int decimals_of(double scale) noexcept {
  if (scale <= 0) return 0;
  int d = 0;
  double s = scale;
  while (d < 9 && std::fabs(s - std::round(s)) > 1e-9) {
    s *= 10;
    ++d;
  }
  return d;
}

bool decimal_scale(double scale, std::int64_t& m, int& d) noexcept {
  // the scales of the catalog, without the search below
  struct Known {
    double scale;
    std::int64_t m;
    int d;
  };
  static constexpr Known kKnown[] = {{1.0, 1, 0}, {0.01, 1, 2}, {0.1, 1, 1},  {0.001, 1, 3},
                                     {0.5, 5, 1}, {1e-7, 1, 7}, {0.05, 5, 2}, {0.0001, 1, 4}};
  for (const Known& k : kKnown)
    if (scale == k.scale) {
      m = k.m;
      d = k.d;
      return true;
    }
  d = decimals_of(scale);
  const double x = scale * kPow10[d];
  if (!(scale > 0) || std::fabs(x - std::round(x)) > 1e-9 || x > 1e9) return false;
  m = std::llround(x);
  return true;
}

double scaled_slow(std::int64_t iv, double scale) noexcept {
  std::int64_t m = 0, mant = 0;
  int d = 0;
  if (decimal_scale(scale, m, d) && !__builtin_mul_overflow(iv, m, &mant) &&
      mant > -(std::int64_t{1} << 53) && mant < (std::int64_t{1} << 53))
    return static_cast<double>(mant) / kPow10[d];
  return static_cast<double>(iv) * scale;
}

std::string fmt_number(double v, int decimals) {
  char b[64];
  auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, decimals);
  if (r.ec == std::errc()) return std::string(b, r.ptr);
  const int n = std::snprintf(nullptr, 0, "%.*f", decimals, v);
  if (n <= 0) return std::string();
  std::string s(static_cast<std::size_t>(n) + 1, '\0');  // with snprintf's terminator
  const int written = std::snprintf(s.data(), s.size(), "%.*f", decimals, v);
  s.resize(static_cast<std::size_t>(std::clamp(written, 0, n)));
  return s;
}

bool all_printable(std::string_view s) noexcept {
  for (unsigned char c : s)
    if (c < 0x20 || c >= 0x7F) return false;
  return true;
}

bool parse_number(std::string_view s, double& out) noexcept {
  if (s.empty()) return false;
  std::size_t i = 0;
  bool neg = false;
  if (s[0] == '-' || s[0] == '+') {
    neg = s[0] == '-';
    i = 1;
  }
  double v = 0, frac = 0.1;
  bool digits = false, point = false;
  for (; i < s.size(); ++i) {
    char c = s[i];
    if (c >= '0' && c <= '9') {
      digits = true;
      if (point) {
        v += (c - '0') * frac;
        frac /= 10;
      } else {
        v = v * 10 + (c - '0');
      }
    } else if (c == '.' && !point) {
      point = true;
    } else {
      return false;
    }
  }
  if (!digits) return false;
  out = neg ? -v : v;
  return true;
}

}  // namespace top::detail
