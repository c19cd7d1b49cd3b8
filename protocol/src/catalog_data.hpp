// Internal: the per-dialect tables, defined in catalog_skydroid.cpp and
// catalog_topotek.cpp.
#pragma once

#include <span>

#include "top/catalog.hpp"

namespace top::detail {

// One bit per model, for the `models` of the tables (catalog and device).
inline constexpr ModelSet c10 = model_bit(Model::c10);
inline constexpr ModelSet c10pro = model_bit(Model::c10pro);
inline constexpr ModelSet c12 = model_bit(Model::c12);
inline constexpr ModelSet c13 = model_bit(Model::c13);
inline constexpr ModelSet c20 = model_bit(Model::c20);
inline constexpr ModelSet sip = model_bit(Model::sip);

std::span<const CommandSpec> skydroid_table() noexcept;
std::span<const CommandSpec> topotek_table() noexcept;

}  // namespace top::detail
