// Swapping a struct member by member (std::swap's three moves of a Frame
// cost the stream decoder a sixth of its speed, BM_stream_decoder): the one
// home of the pattern for Finding, Frame and StreamItem. Each member is
// swapped as `swap` finds it by its type (a string's or vector's own swap,
// top::swap for a Frame or Finding).
#pragma once

#include <utility>

namespace top::detail {

template <class T, class... M>
void swap_members(T& a, T& b, M T::*... member) noexcept {
  using std::swap;
  (swap(a.*member, b.*member), ...);
}

}  // namespace top::detail
