#include "top/catalog.hpp"

#include <array>
#include <cstdint>

#include "catalog_data.hpp"

namespace top {

bool CommandSpec::has_control(char control) const noexcept {
  for (const FormSpec& f : forms)
    if (f.control == control) return true;
  return false;
}

std::span<const CommandSpec> commands(Dialect d) noexcept {
  switch (d) {
    case Dialect::skydroid:
      return detail::skydroid_table();
    case Dialect::topotek:
      return detail::topotek_table();
    case Dialect::unknown:
      break;
  }
  return {};
}

namespace {

constexpr std::size_t kSlots = ident_slots;

struct Index {
  std::array<const CommandSpec*, kSlots> slot[2];
  Index() {
    for (auto& s : slot) s.fill(nullptr);
    build(0, commands(Dialect::skydroid));
    build(1, commands(Dialect::topotek));
  }
  void build(int d, std::span<const CommandSpec> table) {
    for (const CommandSpec& c : table) {
      int k = ident_index(c.ident);
      if (k >= 0 && !slot[d][static_cast<std::size_t>(k)])
        slot[d][static_cast<std::size_t>(k)] = &c;
    }
  }
};

const Index& index() {
  static const Index idx;
  return idx;
}

}  // namespace

const CommandSpec* find_command(Dialect d, std::string_view ident) noexcept {
  if (d == Dialect::unknown) return nullptr;
  int k = ident_index(ident);
  if (k < 0) return nullptr;
  return index().slot[d == Dialect::skydroid ? 0 : 1][static_cast<std::size_t>(k)];
}

const CommandSpec* find_any(std::string_view ident, Dialect preferred) noexcept {
  if (preferred == Dialect::unknown) preferred = Dialect::skydroid;
  if (const CommandSpec* c = find_command(preferred, ident)) return c;
  Dialect other = preferred == Dialect::skydroid ? Dialect::topotek : Dialect::skydroid;
  return find_command(other, ident);
}

Header choose_header(Dialect dialect, char address_class, std::size_t data_length) noexcept {
  if (data_length > max_data_ext8) return Header::ext16;
  if (data_length > max_data_hex) return Header::ext8;
  if (dialect == Dialect::skydroid) {
    // SkyDroid 2.2.2: every G-class command uses #TP, variable ones too.
    if (address_class == 'G' || data_length == 2) return Header::fixed;
    return Header::variable;
  }
  if (address_class == 'M') return Header::variable;
  return data_length == 2 ? Header::fixed : Header::variable;
}

}  // namespace top
