// Internal: character classes as 256-entry tables.
#pragma once

#include "top/text.hpp"

namespace top::detail {

using top::hex_value;
inline bool is_hex(char c) noexcept { return hex_value(c) >= 0; }
inline bool is_lower_hex(char c) noexcept { return c >= 'a' && c <= 'f'; }

}  // namespace top::detail
