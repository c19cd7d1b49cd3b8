#include "decode_cache.hpp"

#include <algorithm>
#include <bit>

namespace top {

DecodeCache::DecodeCache(std::size_t slots) {
  const std::size_t n = std::bit_ceil(std::clamp<std::size_t>(slots, 1, std::size_t{1} << 20));
  slots_ = std::make_unique<detail::ShapeSlot[]>(n);
  shift_ = 32 - static_cast<unsigned>(std::countr_zero(n));
}

DecodeCache::~DecodeCache() = default;

}  // namespace top
