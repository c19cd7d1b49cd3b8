// The command catalog: every identifier of both documents, written once.
//
// Each entry says which dialect defines it, its address class, the forms it
// takes (read request, read response, write, write reply), the data layout
// of each form as named typed fields with units, scales, enums and ranges,
// the models that support it, and the section of the document it comes
// from. Enums, lookups, the fuzz dictionary and the CLI listings derive from
// these tables.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "top/frame.hpp"

namespace top {

enum class Dialect : std::uint8_t { unknown, skydroid, topotek };

enum class Model : std::uint8_t { unknown, c10, c10pro, c12, c13, c20, sip };

std::string_view to_string(Dialect d) noexcept;  // "skydroid", "topotek"
std::string_view to_string(Model m) noexcept;    // "c10", ..., "sip"
std::optional<Dialect> dialect_from_string(std::string_view s) noexcept;
std::optional<Model> model_from_string(std::string_view s) noexcept;
// The dialect a model speaks (sip -> topotek, the C series -> skydroid).
Dialect dialect_of(Model m) noexcept;
// Every real model, in documentation order.
std::span<const Model> all_models() noexcept;

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
  nmea,       // hemisphere letter + NMEA dddmm.mmmm, decoded to degrees
  raw         // bytes shown as they are; no value
};

std::string_view to_string(FieldKind k) noexcept;

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

// Who sends a form.
enum class Role : std::uint8_t { request, response, any };

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

  bool supports(Model m) const noexcept {
    return m == Model::unknown || (models & model_bit(m)) != 0;
  }
  bool has_control(char control) const noexcept;
};

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
