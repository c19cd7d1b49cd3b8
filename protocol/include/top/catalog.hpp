// The command catalog: every identifier of both documents, written once.
//
// Each entry says which dialect defines it, its address class, the forms it
// takes (read request, read response, write, write reply), the data layout
// of each form as named typed fields with units, scales, enums and ranges,
// the models that support it, and the section of the document it comes
// from. Enums, lookups, the fuzz dictionary and the CLI listings derive from
// these tables.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "top/frame.hpp"

namespace top {

enum class Dialect : std::uint8_t { unknown, skydroid, topotek };

enum class Model : std::uint8_t { unknown, c10, c10pro, c12, c13, c20, sip };

// Names (src/names.cpp holds each enum's table): to_string gives the name,
// *_from_string the enumerator or nullopt. "auto" also reads as unknown.
std::string_view to_string(Dialect d) noexcept;  // "unknown", "skydroid", "topotek"
std::string_view to_string(Model m) noexcept;    // "unknown", "c10", ..., "sip"
std::optional<Dialect> dialect_from_string(std::string_view s) noexcept;
std::optional<Model> model_from_string(std::string_view s) noexcept;
// The dialect a model speaks (sip -> topotek, the C series -> skydroid).
Dialect dialect_of(Model m) noexcept;
// Every real model, in documentation order (every enumerator but unknown).
std::span<const Model> all_models() noexcept;
// Their names joined: model_list(", ", " or ") == "c10, c10pro, ... or sip".
std::string model_list(std::string_view separator = " ", std::string_view last = " ");

// A set of models as a bit mask.
using ModelSet = std::uint8_t;
constexpr ModelSet model_bit(Model m) noexcept {
  return static_cast<ModelSet>(1u << static_cast<unsigned>(m));
}
inline constexpr ModelSet skydroid_models = model_bit(Model::c10) | model_bit(Model::c10pro) |
                                            model_bit(Model::c12) | model_bit(Model::c13) |
                                            model_bit(Model::c20);
inline constexpr ModelSet topotek_models = model_bit(Model::sip);

// How a field's bytes are read.
enum class FieldKind : std::uint8_t {
  hex_u,      // unsigned hex digits, most significant first
  hex_s,      // two's complement hex digits (4 bits per digit)
  dec_u,      // unsigned decimal digits
  enum_hex,   // hex digits that name an enum value
  enum_char,  // one or more characters that name an enum value (no number)
  text,       // printable ASCII text (IP address, version string)
  number,     // decimal number as text, optional sign and point ("-12.5")
  le_i16,     // binary little-endian signed 16-bit
  le_u16,     // binary little-endian unsigned 16-bit
  le_i32,     // binary little-endian signed 32-bit
  be_i16,     // binary big-endian signed 16-bit (field: Topotek LOC)
  be_u16,     // binary big-endian unsigned 16-bit (field: Topotek LOC)
  u8,         // one binary byte, unsigned (field: the Topotek ODR record count)
  nmea,       // hemisphere letter + NMEA dddmm.mmmm, decoded to degrees
  raw         // bytes shown as they are; no value
};

// Whether a kind holds an integer number: hex or decimal digits, or a
// binary integer (not an enum, text, number text, NMEA or raw bytes).
constexpr bool is_integer_kind(FieldKind k) noexcept {
  switch (k) {
    case FieldKind::hex_u:
    case FieldKind::hex_s:
    case FieldKind::dec_u:
    case FieldKind::le_i16:
    case FieldKind::le_u16:
    case FieldKind::le_i32:
    case FieldKind::be_i16:
    case FieldKind::be_u16:
    case FieldKind::u8:
      return true;
    default:
      return false;
  }
}

std::string_view to_string(FieldKind k) noexcept;  // "hex_u", ...
std::optional<FieldKind> field_kind_from_string(std::string_view s) noexcept;

struct EnumValue {
  std::int64_t value;  // numeric value (enum_hex) or first char (enum_char)
  std::string_view name;
};

struct FieldSpec {
  std::string_view name;  // snake_case, stable: "yaw", "speed"
  FieldKind kind = FieldKind::hex_u;
  std::uint16_t width = 2;           // chars (bytes for le_*); 0 = rest of the data
  double scale = 1.0;                // value = raw * scale
  std::string_view unit;             // "deg", "deg/s", "MB", "degC", "m", ""
  double min = 0, max = -1;          // allowed range in scaled units (min > max: none)
  std::span<const EnumValue> enums;  // for enum_* kinds (and hex_u labels)
  std::string_view none;             // placeholder meaning "no value" ("NNNN")
  std::string_view note;             // one line from the document
};

// Who sends a form. A new role goes before `any` (kept last), with its name
// in names.cpp, which a static_assert checks.
enum class Role : std::uint8_t { request, response, any };
std::string_view to_string(Role r) noexcept;  // "request", "response", "any"
std::optional<Role> role_from_string(std::string_view s) noexcept;

struct FormSpec {
  char control = 'w';  // 'r' or 'w'
  Role role = Role::any;
  std::uint16_t min_length = 0;  // data length range this form covers
  std::uint16_t max_length = 0;
  std::span<const FieldSpec> fields;
  std::string_view note;
  // Whole data that means "no value" (SkyDroid SDC all zero: no card); the
  // note says what it means.
  std::string_view none;
  // Records that follow the fields (field: the Topotek ODR detections): the
  // last of `fields` counts them, and each is these fields in order, all of
  // a fixed width. Empty: the form is its fields.
  std::span<const FieldSpec> record;
  // Empty for a form the document gives. A form only the field shows (real
  // units, or the drivers written against them) names its source here: the
  // driver file and PR, a real unit's log, a station's note
  // (docs/sources/ardupilot.md). topsim's document profile does not take it.
  std::string_view evidence;

  bool from_field() const noexcept { return !evidence.empty(); }
};

struct CommandSpec {
  std::string_view ident;  // "GAY"
  Dialect dialect = Dialect::unknown;
  char address = 'G';        // class: G, M, D or E (the device side)
  std::string_view title;    // "gimbal yaw angle"
  std::string_view section;  // "SkyDroid 3.3.1" / "Topotek 4.3.1"
  ModelSet models = 0;
  std::span<const FormSpec> forms;
  std::string_view note;  // errata, caveats
  // Empty for a command of a document. A command neither document lists
  // names the field's source here (its section starts "field: "); every
  // one of its forms is then field evidence too.
  std::string_view evidence;

  bool from_field() const noexcept { return !evidence.empty(); }

  bool supports(Model m) const noexcept {
    return m == Model::unknown || (models & model_bit(m)) != 0;
  }
  bool has_control(char control) const noexcept;
};

// Identifiers are three chars of [A-Z0-9]: ident_index() gives each one a
// slot in [0, ident_slots) (base 36, digits A-Z then 0-9, first char most
// significant), -1 for anything else; ident_chars[d] is digit d.
inline constexpr char ident_chars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
inline constexpr int ident_base = 36;
inline constexpr std::size_t ident_slots = std::size_t{36} * 36 * 36;
namespace detail {
inline constexpr std::array<std::int16_t, 256> kIdentDigit = [] {
  std::array<std::int16_t, 256> t{};
  for (auto& v : t) v = -1;
  for (int d = 0; d < ident_base; ++d)
    t[static_cast<unsigned char>(ident_chars[d])] = static_cast<std::int16_t>(d);
  return t;
}();
}  // namespace detail
// Asked for every frame (topdump counts identifiers by it), so inline.
inline int ident_index(const char ident[3]) noexcept {
  const int a = detail::kIdentDigit[static_cast<unsigned char>(ident[0])];
  const int b = detail::kIdentDigit[static_cast<unsigned char>(ident[1])];
  const int c = detail::kIdentDigit[static_cast<unsigned char>(ident[2])];
  if ((a | b | c) < 0) return -1;
  return (a * ident_base + b) * ident_base + c;
}
inline int ident_index(std::string_view ident) noexcept {
  return ident.size() == 3 ? ident_index(ident.data()) : -1;
}
// The identifier of a slot: ident_of(ident_index("GAY")) == "GAY".
inline std::string ident_of(std::size_t slot) {
  return {ident_chars[slot / 1296 % 36], ident_chars[slot / 36 % 36], ident_chars[slot % 36]};
}

// Every command of a dialect, in document order.
std::span<const CommandSpec> commands(Dialect d) noexcept;
// The entry for an identifier in a dialect, or nullptr.
const CommandSpec* find_command(Dialect d, std::string_view ident) noexcept;
// The entry in either dialect, preferring `preferred` (for detection).
const CommandSpec* find_any(std::string_view ident, Dialect preferred = Dialect::skydroid) noexcept;

// The header a sender of `dialect` uses for a frame to or from `address`
// class with `data_length` bytes of data: SkyDroid puts every G-class command
// under #TP and uses #TP for length 2; Topotek uses #tp for M-class, #TP for
// length 2 otherwise, and #tP/#Tp past 15.
Header choose_header(Dialect dialect, char address_class, std::size_t data_length) noexcept;

}  // namespace top
