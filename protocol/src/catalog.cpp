#include "top/catalog.hpp"

#include <array>
#include <cstdint>

#include "catalog_data.hpp"

namespace top {

std::string_view to_string(Dialect d) noexcept {
  switch (d) {
    case Dialect::skydroid:
      return "skydroid";
    case Dialect::topotek:
      return "topotek";
    case Dialect::unknown:
      break;
  }
  return "unknown";
}

std::string_view to_string(Model m) noexcept {
  switch (m) {
    case Model::c10:
      return "c10";
    case Model::c10pro:
      return "c10pro";
    case Model::c12:
      return "c12";
    case Model::c13:
      return "c13";
    case Model::c20:
      return "c20";
    case Model::sip:
      return "sip";
    case Model::unknown:
      break;
  }
  return "unknown";
}

std::optional<Dialect> dialect_from_string(std::string_view s) noexcept {
  if (s == "skydroid") return Dialect::skydroid;
  if (s == "topotek") return Dialect::topotek;
  if (s == "auto" || s == "unknown") return Dialect::unknown;
  return std::nullopt;
}

std::optional<Model> model_from_string(std::string_view s) noexcept {
  for (Model m : all_models())
    if (to_string(m) == s) return m;
  if (s == "auto" || s == "unknown") return Model::unknown;
  return std::nullopt;
}

Dialect dialect_of(Model m) noexcept {
  switch (m) {
    case Model::sip:
      return Dialect::topotek;
    case Model::unknown:
      return Dialect::unknown;
    default:
      return Dialect::skydroid;
  }
}

std::span<const Model> all_models() noexcept {
  static constexpr Model kModels[] = {Model::c10, Model::c10pro, Model::c12,
                                      Model::c13, Model::c20,    Model::sip};
  return kModels;
}

std::string_view to_string(FieldKind k) noexcept {
  switch (k) {
    case FieldKind::hex_u:
      return "hex_u";
    case FieldKind::hex_s:
      return "hex_s";
    case FieldKind::dec_u:
      return "dec_u";
    case FieldKind::enum_hex:
      return "enum_hex";
    case FieldKind::enum_char:
      return "enum_char";
    case FieldKind::text:
      return "text";
    case FieldKind::number:
      return "number";
    case FieldKind::le_i16:
      return "le_i16";
    case FieldKind::le_u16:
      return "le_u16";
    case FieldKind::le_i32:
      return "le_i32";
    case FieldKind::nmea:
      return "nmea";
    case FieldKind::raw:
      return "raw";
  }
  return "?";
}

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

// Identifiers are three chars of [A-Z0-9]: a direct index of 36^3 slots
// per dialect, built once.
constexpr int kAlphabet = 36;
constexpr int kSlots = kAlphabet * kAlphabet * kAlphabet;

// [A-Z] -> 0-25, [0-9] -> 26-35, anything else -> -1.
constexpr std::array<std::int16_t, 256> kCharIndex = [] {
  std::array<std::int16_t, 256> t{};
  for (auto& v : t) v = -1;
  for (int c = 'A'; c <= 'Z'; ++c)
    t[static_cast<std::size_t>(c)] = static_cast<std::int16_t>(c - 'A');
  for (int c = '0'; c <= '9'; ++c)
    t[static_cast<std::size_t>(c)] = static_cast<std::int16_t>(26 + c - '0');
  return t;
}();

int ident_index(std::string_view ident) noexcept {
  if (ident.size() != 3) return -1;
  int a = kCharIndex[static_cast<unsigned char>(ident[0])];
  int b = kCharIndex[static_cast<unsigned char>(ident[1])];
  int c = kCharIndex[static_cast<unsigned char>(ident[2])];
  if ((a | b | c) < 0) return -1;
  return (a * kAlphabet + b) * kAlphabet + c;
}

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
