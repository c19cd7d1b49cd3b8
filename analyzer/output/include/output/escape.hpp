// Strings for JSON and messages; the escapes of bytes are the library's
// (top/text.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "top/detail/text.hpp"

namespace topdump {

namespace detail {
// Bytes that go into a JSON string as they are: printable ASCII but '"'
// and '\\'.
inline constexpr std::array<bool, 256> kJsonPlain = [] {
  std::array<bool, 256> t{};
  for (int c = 0x20; c < 0x7F; ++c) t[static_cast<std::size_t>(c)] = c != '"' && c != '\\';
  return t;
}();
}  // namespace detail

// True when every byte goes into a JSON string as it is (no escape
// needed). Eight bytes at a time: the JSON writer asks this of every string
// of every frame.
inline bool json_plain(std::string_view s) noexcept {
  constexpr std::uint64_t kOnes = 0x0101010101010101ull, kHigh = 0x8080808080808080ull;
  const char* p = s.data();
  std::size_t n = s.size();
  for (; n >= 8; p += 8, n -= 8) {
    std::uint64_t x;
    std::memcpy(&x, p, 8);
    const std::uint64_t q = x ^ (kOnes * '"'), b = x ^ (kOnes * '\\');
    const std::uint64_t below = (x - kOnes * 0x20) & ~x;  // a byte < 0x20
    const std::uint64_t above = (x + kOnes) | x;          // a byte >= 0x7F
    const std::uint64_t quote = (q - kOnes) & ~q, slash = (b - kOnes) & ~b;
    if ((below | above | quote | slash) & kHigh) return false;
  }
  for (; n > 0; ++p, --n)
    if (!detail::kJsonPlain[static_cast<unsigned char>(*p)]) return false;
  return true;
}

using top::ascii_text;
using top::escape;
using top::unescape;

}  // namespace topdump
