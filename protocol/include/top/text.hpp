// Bytes as text and back: hex digits, and the escapes every tool shows
// bytes with (topdump's lines and JSON, topconf's reports, command-line
// frames).
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
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

// The pieces joined, in one allocation: a chain of operator+ grows the
// string piece by piece, an allocation per growth, and a message built that
// way (a finding's, a capture note's) cost more than the check that found
// it. Numbers as std::to_string gives them stay in its small-string buffer.
inline std::string cat(std::initializer_list<std::string_view> parts) {
  std::size_t n = 0;
  for (std::string_view p : parts) n += p.size();
  std::string s;
  s.reserve(n);
  for (std::string_view p : parts) s.append(p);
  return s;
}

// Printable ASCII as is; "\\" for a backslash, "\r" and "\n", anything else
// as \xNN (uppercase), so the result round-trips through unescape().
std::string escape(std::string_view bytes);

// Text for XML and HTML, element content or attribute value (topdump's
// report and its SVG plots, topconf's JUnit and HTML reports): & < > " as
// entities (attributes are always double-quoted, so ' stays); the control
// bytes XML 1.0 does not allow (all below 0x20 but tab and newline) as
// escape() writes them ("\r", "\x01"), so a byte reads the same in a report
// as in topdump's lines; every other byte as it is.
std::string markup_escape(std::string_view text);

// Turns "\x23", "\r", "\n", "\t", "\0", "\\" into bytes. Returns nullopt and
// sets `error` (with the position) on a malformed escape.
std::optional<std::string> unescape(std::string_view arg, std::string& error);

// The bytes a JSON string of tests/vectors stands for: each code point
// U+0000-U+00FF (one or two UTF-8 bytes) is one byte; nullopt for anything
// else.
std::optional<std::string> bytes_from_utf8(std::string_view utf8);

// A message as text that is valid UTF-8 (ASCII): bytes 0x80-0xFF as \xNN,
// everything else as it is (messages quote input through escape(); this
// keeps a byte that slipped through from breaking a JSON line).
std::string ascii_text(std::string_view message);

}  // namespace top
