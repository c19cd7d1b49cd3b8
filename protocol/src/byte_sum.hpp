// Internal: byte sums and a short copy, in a header so that checksum()
// (frame.cpp) and the parser (frame_parse.cpp, frame_checksum.cpp) inline
// them: every frame is summed once or more.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace top::detail {

// The sum of n bytes, eight at a time.
inline unsigned byte_sum(const char* p, std::size_t n) noexcept {
  constexpr std::uint64_t kLow = 0x00FF00FF00FF00FFull;
  unsigned s = 0;
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t x;
    std::memcpy(&x, p + i, 8);
    // four 16-bit lanes of byte pairs, then their total in the top lane
    const std::uint64_t pairs = (x & kLow) + ((x >> 8) & kLow);
    s += static_cast<unsigned>((pairs * 0x0001000100010001ull) >> 48);
  }
  for (; i < n; ++i) s += static_cast<unsigned char>(p[i]);
  return s;
}

// byte_sum for n >= 8 without a loop over the last n % 8 bytes: the
// eight bytes that end at p + n make the last word, less the low bytes that
// the words before it summed already.
inline unsigned byte_sum8(const char* p, std::size_t n) noexcept {
  constexpr std::uint64_t kLow = 0x00FF00FF00FF00FFull;
  auto sum = [](std::uint64_t x) {
    const std::uint64_t pairs = (x & kLow) + ((x >> 8) & kLow);
    return static_cast<unsigned>((pairs * 0x0001000100010001ull) >> 48);
  };
  unsigned s = 0;
  std::size_t i = 0;
  std::uint64_t x;
  for (; i + 8 < n; i += 8) {
    std::memcpy(&x, p + i, 8);
    s += sum(x);
  }
  std::memcpy(&x, p + n - 8, 8);
  const std::size_t seen = i + 8 - n;  // 0-7 low bytes counted above
  if (std::endian::native == std::endian::little)
    x &= ~std::uint64_t{0} << (8 * seen);
  else
    x &= ~std::uint64_t{0} >> (8 * seen);
  return s + sum(x);
}

// dst[0, n) = src[0, n) for 8 <= n <= 32 in four eight-byte moves, the last
// ones overlapping (no length-dependent branch, no string instruction).
inline void copy_short(char* dst, const char* src, std::size_t n) noexcept {
  for (std::size_t j = 0; j < 32; j += 8) {
    const std::size_t at = std::min(j, n - 8);
    std::uint64_t x;
    std::memcpy(&x, src + at, 8);
    std::memcpy(dst + at, &x, 8);
  }
}

}  // namespace top::detail
