// Internal: the numbers of the catalog's fields: scales as decimal
// fractions, values scaled exactly, fixed-point text.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "top/detail/decimal.hpp"

namespace top::detail {

// printf("%.*f") (std::to_chars promises the same text, several times
// faster); past 64 characters (a huge decimal number field) snprintf sizes it.
inline constexpr double kPow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

// A scale as m / 10^d with m an integer (0.01 -> 1/10^2, 0.5 -> 5/10^1);
// false when it is no decimal fraction (1/3) or needs more than 9 decimals.
bool decimal_scale(double scale, std::int64_t& m, int& d) noexcept;

// integer * scale, correctly rounded when the scale is a decimal fraction:
// 0.01 * -295 gives -2.95 rather than -2.9500000000000002.
double scaled_slow(std::int64_t iv, double scale) noexcept;

inline double scaled(std::int64_t iv, double scale) noexcept {
  constexpr std::int64_t kExact = std::int64_t{1} << 53;  // integers a double holds
  if (iv > -kExact && iv < kExact) {                      // the catalog's usual scales, inline
    if (scale == 1.0) return static_cast<double>(iv);
    if (scale == 0.01) return static_cast<double>(iv) / 100.0;
    if (scale == 0.1) return static_cast<double>(iv) / 10.0;
  }
  return scaled_slow(iv, scale);
}

// printf("%.*f", decimals, v).
std::string fmt_number(double v, int decimals);

// Every byte printable ASCII (0x20-0x7E).
bool all_printable(std::string_view s) noexcept;
// Parses "[-+]digits[.digits]"; false on anything else.
bool parse_number(std::string_view s, double& out) noexcept;

}  // namespace top::detail
