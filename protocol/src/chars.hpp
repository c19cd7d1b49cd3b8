// Internal: character classes; cat() for finding messages (top/detail/text.hpp).
#pragma once

#include <string>
#include <string_view>

#include "top/detail/text.hpp"
#include "top/frame.hpp"

namespace top::detail {

using top::hex_value;
inline bool is_hex(char c) noexcept { return hex_value(c) >= 0; }
inline bool is_lower_hex(char c) noexcept { return char_is(c, kClassLowerHex); }

using top::cat;  // top/detail/text.hpp

}  // namespace top::detail
