// Not part of the API (not installed): the text helpers the tree's tools
// share. The library's finding messages are joined with cat(); topdump's
// and topconf's reports escape markup; JSON writers keep messages ASCII; the
// test vectors and the fuzz replays read bytes from JSON strings. The names
// stay in namespace top.
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "top/text.hpp"

namespace top {

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

// Text for XML and HTML, element content or attribute value (topdump's
// report and its SVG plots, topconf's JUnit and HTML reports): & < > " as
// entities (attributes are always double-quoted, so ' stays); the control
// bytes XML 1.0 does not allow (all below 0x20 but tab and newline) as
// escape() writes them ("\r", "\x01"), so a byte reads the same in a report
// as in topdump's lines; every other byte as it is.
std::string markup_escape(std::string_view text);

// The bytes a JSON string of tests/vectors stands for: each code point
// U+0000-U+00FF (one or two UTF-8 bytes) is one byte; nullopt for anything
// else.
std::optional<std::string> bytes_from_utf8(std::string_view utf8);

// A message as text that is valid UTF-8 (ASCII): bytes 0x80-0xFF as \xNN,
// everything else as it is (messages quote input through escape(); this
// keeps a byte that slipped through from breaking a JSON line).
std::string ascii_text(std::string_view message);

}  // namespace top
