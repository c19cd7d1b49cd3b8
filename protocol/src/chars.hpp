// Internal: character classes as 256-entry tables.
#pragma once

#include <array>
#include <cstdint>

namespace top::detail {

inline constexpr std::array<std::int8_t, 256> kHexValue = [] {
  std::array<std::int8_t, 256> t{};
  for (auto& v : t) v = -1;
  for (int c = '0'; c <= '9'; ++c)
    t[static_cast<std::size_t>(c)] = static_cast<std::int8_t>(c - '0');
  for (int c = 'A'; c <= 'F'; ++c)
    t[static_cast<std::size_t>(c)] = static_cast<std::int8_t>(c - 'A' + 10);
  for (int c = 'a'; c <= 'f'; ++c)
    t[static_cast<std::size_t>(c)] = static_cast<std::int8_t>(c - 'a' + 10);
  return t;
}();

// Value of a hex digit (either case), -1 otherwise.
inline int hex_value(char c) noexcept { return kHexValue[static_cast<unsigned char>(c)]; }
inline bool is_hex(char c) noexcept { return hex_value(c) >= 0; }
inline bool is_lower_hex(char c) noexcept { return c >= 'a' && c <= 'f'; }

}  // namespace top::detail
