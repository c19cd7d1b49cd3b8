// The text of every enum of the public headers, one table each, and the
// lookups both ways. Each table is indexed by its enum; a static_assert
// keeps its length equal to the enum's (add an enumerator, add its name).
#include <array>
#include <iterator>

#include "top/catalog.hpp"
#include "top/enum_names.hpp"
#include "top/frame.hpp"

namespace top {

namespace {

constexpr std::string_view kDialect[] = {"unknown", "skydroid", "topotek"};
static_assert(std::size(kDialect) == static_cast<std::size_t>(Dialect::topotek) + 1);

// all_models() lists every one but unknown, in this order.
constexpr std::string_view kModel[] = {"unknown", "c10", "c10pro", "c12", "c13", "c20", "sip"};
static_assert(std::size(kModel) == static_cast<std::size_t>(Model::sip) + 1);

constexpr std::string_view kRole[] = {"request", "response", "any"};
static_assert(std::size(kRole) == static_cast<std::size_t>(Role::any) + 1);

constexpr std::string_view kHeader[] = {"#TP", "#tp", "#tP", "#Tp", "#P"};
static_assert(std::size(kHeader) == static_cast<std::size_t>(Header::tmp_quirk) + 1);

constexpr std::string_view kHeaderDescription[] = {
    "fixed, length 2", "variable, one hex length char", "extended, one raw length byte",
    "extended, two raw length bytes", "malformed Topotek TMP form"};
static_assert(std::size(kHeaderDescription) == std::size(kHeader));

constexpr std::string_view kFieldKind[] = {"hex_u",  "hex_s",  "dec_u",  "enum_hex", "enum_char",
                                           "text",   "number", "le_i16", "le_u16",   "le_i32",
                                           "be_i16", "be_u16", "u8",     "nmea",     "raw"};
static_assert(std::size(kFieldKind) == static_cast<std::size_t>(FieldKind::raw) + 1);

}  // namespace

std::string_view to_string(Dialect d) noexcept { return enum_name(kDialect, d, "unknown"); }
std::string_view to_string(Model m) noexcept { return enum_name(kModel, m, "unknown"); }
std::string_view to_string(Role r) noexcept { return enum_name(kRole, r, "any"); }
std::string_view to_string(Header h) noexcept { return enum_name(kHeader, h, "?"); }
std::string_view describe(Header h) noexcept { return enum_name(kHeaderDescription, h, "?"); }

std::string_view describe_address(char a) noexcept {
  switch (a) {
    case 'U':
      return "UART/UDP client";
    case 'M':
      return "lens";
    case 'D':
      return "system/image";
    case 'E':
      return "auxiliary";
    case 'P':
      return "network client";
    case 'G':
      return "gimbal";
    default:
      return {};
  }
}
std::string_view to_string(FieldKind k) noexcept { return enum_name(kFieldKind, k, "?"); }

std::optional<Dialect> dialect_from_string(std::string_view s) noexcept {
  if (s == "auto") return Dialect::unknown;
  return enum_from_name<Dialect>(kDialect, s);
}

std::optional<Model> model_from_string(std::string_view s) noexcept {
  if (s == "auto") return Model::unknown;
  return enum_from_name<Model>(kModel, s);
}

std::optional<Role> role_from_string(std::string_view s) noexcept {
  return enum_from_name<Role>(kRole, s);
}

std::optional<Header> header_from_string(std::string_view s) noexcept {
  return enum_from_name<Header>(kHeader, s);
}

std::optional<FieldKind> field_kind_from_string(std::string_view s) noexcept {
  return enum_from_name<FieldKind>(kFieldKind, s);
}

std::span<const Model> all_models() noexcept {
  static constexpr auto kAll = [] {
    std::array<Model, std::size(kModel) - 1> a{};
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = static_cast<Model>(i + 1);
    return a;
  }();
  return kAll;
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

std::string model_list(std::string_view separator, std::string_view last) {
  std::string s;
  const auto all = all_models();
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i) s += i + 1 == all.size() ? last : separator;
    s += to_string(all[i]);
  }
  return s;
}

}  // namespace top
