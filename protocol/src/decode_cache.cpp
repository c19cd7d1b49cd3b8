// DecodeCache (top/detail/decode_cache.hpp): its slots are shape_slot.hpp's.
#include "top/detail/decode_cache.hpp"

#include <algorithm>
#include <bit>

#include "shape_slot.hpp"

namespace top::detail {

DecodeCache::DecodeCache(std::size_t slots) {
  count_ = std::bit_ceil(std::clamp<std::size_t>(slots, 1, std::size_t{1} << 20));
  shift_ = 32 - static_cast<unsigned>(std::countr_zero(count_));
}

DecodeCache::~DecodeCache() = default;

}  // namespace top::detail
