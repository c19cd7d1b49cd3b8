// Bytes as text and back: hex digits, and the escapes every tool shows
// bytes with (topdump's lines and JSON, topconf's reports, command-line
// frames). The tree's own text helpers (markup, ASCII, joining) are in
// top/detail/text.hpp, which is not installed.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace top {

namespace detail {
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
}  // namespace detail

// Value of a hex digit (either case), -1 otherwise.
inline int hex_value(char c) noexcept { return detail::kHexValue[static_cast<unsigned char>(c)]; }

// Printable ASCII as is; "\\" for a backslash, "\r" and "\n", anything else
// as \xNN (uppercase), so the result round-trips through unescape().
std::string escape(std::string_view bytes);

// Turns "\x23", "\r", "\n", "\t", "\0", "\\" into bytes. Returns nullopt and
// sets `error` (with the position) on a malformed escape.
std::optional<std::string> unescape(std::string_view arg, std::string& error);

}  // namespace top
