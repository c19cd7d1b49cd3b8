// The text of an enum, both ways, from one array of names indexed by the
// enum: the library's enums (names.cpp), the device model's (device.cpp) and
// topconf's (verdicts, failure classes, ...). Next to each array, a
// static_assert keeps its length equal to the enum's:
//   static_assert(std::size(kVerdict) == static_cast<std::size_t>(Verdict::error) + 1);
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace top {

// names[e], or `other` for a value past the table.
template <class E, std::size_t N>
constexpr std::string_view enum_name(const std::string_view (&names)[N], E e,
                                     std::string_view other = "?") noexcept {
  const auto i = static_cast<std::size_t>(e);
  return i < N ? names[i] : other;
}

// The enumerator whose name is `s`, or nullopt.
template <class E, std::size_t N>
constexpr std::optional<E> enum_from_name(const std::string_view (&names)[N],
                                          std::string_view s) noexcept {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == s) return static_cast<E>(i);
  return std::nullopt;
}

}  // namespace top
