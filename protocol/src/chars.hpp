// Internal: character classes, and building finding messages.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include "top/frame.hpp"
#include "top/text.hpp"

namespace top::detail {

using top::hex_value;
inline bool is_hex(char c) noexcept { return hex_value(c) >= 0; }
inline bool is_lower_hex(char c) noexcept { return char_is(c, kClassLowerHex); }

// The pieces joined, in one allocation (a chain of operator+ grows the
// string piece by piece, an allocation per growth: most of the cost of a
// finding's message).
inline std::string cat(std::initializer_list<std::string_view> parts) {
  std::size_t n = 0;
  for (std::string_view p : parts) n += p.size();
  std::string s;
  s.reserve(n);
  for (std::string_view p : parts) s.append(p);
  return s;
}

}  // namespace top::detail
