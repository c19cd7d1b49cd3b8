// Internal: the per-dialect tables, defined in catalog_skydroid.cpp and
// catalog_topotek.cpp.
#pragma once

#include <span>

#include "top/catalog.hpp"

namespace top::detail {

std::span<const CommandSpec> skydroid_table() noexcept;
std::span<const CommandSpec> topotek_table() noexcept;

}  // namespace top::detail
