// C escapes for bytes given on a command line, and back for display.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace topdump {

// Turns "\x23", "\r", "\n", "\t", "\0", "\\" into bytes. Returns nullopt and
// sets `error` (with the position) on a malformed escape.
std::optional<std::string> unescape(std::string_view arg, std::string& error);

// Printable ASCII as is; anything else as \xNN (and \r \n \\), so the
// result round-trips through unescape().
std::string escape(std::string_view bytes);

// A message as text that is valid UTF-8 (ASCII): bytes 0x80-0xFF as \xNN,
// everything else as it is. Messages quote input through escape(); this
// keeps a byte that slipped through from breaking a JSON line.
std::string ascii_text(std::string_view message);

}  // namespace topdump
