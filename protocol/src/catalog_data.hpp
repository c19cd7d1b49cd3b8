// Internal: the per-dialect tables, defined in catalog_skydroid.cpp and
// catalog_topotek.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

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

// A per-command fact, worked out once at start-up by `make` for every
// catalog command and then read in constant time, by the command's place
// in its dialect's table (the session asks such facts of every frame);
// `make` also answers for a command not in the catalog (a copy).
template <class T, class Make>
class PerCommand {
 public:
  explicit PerCommand(Make make) : make_(make) {
    for (const Dialect d : {Dialect::skydroid, Dialect::topotek}) {
      const std::span<const CommandSpec> t =
          d == Dialect::topotek ? topotek_table() : skydroid_table();
      Rows& r = of_[d == Dialect::topotek];
      r.base = reinterpret_cast<std::uintptr_t>(t.data());
      r.size = t.size();
      for (const CommandSpec& c : t) r.v.push_back(make_(c));
    }
  }
  T operator()(const CommandSpec& cmd) const noexcept {
    const Rows& r = of_[cmd.dialect == Dialect::topotek];
    // unsigned: a command before the table's start wraps past its size
    const std::size_t at = (reinterpret_cast<std::uintptr_t>(&cmd) - r.base) / sizeof(CommandSpec);
    return at < r.size ? r.v[at] : make_(cmd);
  }

 private:
  struct Rows {
    std::uintptr_t base = 0;
    std::size_t size = 0;
    std::vector<T> v;
  };
  Make make_;
  std::array<Rows, 2> of_;  // skydroid, topotek
};

}  // namespace top::detail
