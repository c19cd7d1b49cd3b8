// Internal to decode.cpp and decode_fields.cpp: the decoding context, the
// enum and range judgement every field kind shares, and the fields of a
// form (decode_fields.cpp).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "numbers.hpp"
#include "top/decode.hpp"

namespace top::detail {

struct FormPlan;  // decode_plan.hpp

inline bool role_fits(Role form, Role frame) noexcept {
  return form == Role::any || frame == Role::any || form == frame;
}

inline const EnumValue* find_enum(std::span<const EnumValue> e, std::int64_t v) noexcept {
  for (const EnumValue& x : e)
    if (x.value == v) return &x;
  return nullptr;
}

struct Ctx {
  const Frame& frame;
  Decoded& out;
  bool detail = true;  // DecodeOptions::detail
  bool lowercase_reported = false;
  // `message()` builds the text, only with detail (topdump stats keeps the
  // code, severity and offset of a finding, never its text).
  template <class Message>
  void add(FindingCode code, std::uint32_t offset, Message&& message) {
    out.findings.push_back(make_finding(code, offset, detail ? message() : std::string()));
  }
  // The field's text (text, number, nmea and raw kinds; the bytes of an
  // invalid or "none" field), kept only with detail.
  void keep(FieldValue& fv, std::string_view bytes) const {
    if (detail) fv.text.assign(bytes);
  }
};

// The enum and range checks of a field's number (`value()` gives it scaled,
// asked for only when the field has a range); the enum name when known.
template <class Value>
std::string_view judge(Ctx& ctx, const FieldSpec& spec, std::string_view bytes,
                       std::uint32_t offset, std::int64_t integer, Value&& value) {
  if (!spec.enums.empty()) {
    if (const EnumValue* e = find_enum(spec.enums, integer)) return e->name;
    if (spec.kind == FieldKind::enum_hex || spec.kind == FieldKind::enum_char) {
      ctx.add(FindingCode::value_out_of_range, offset, [&] {
        return cat({spec.name, ": '", bytes, "' is not a documented value"});
      });
      return {};
    }
  }
  if (spec.min > spec.max) return {};
  const double v = value();
  if (v < spec.min - 1e-9 || v > spec.max + 1e-9) {
    int d = decimals_of(spec.scale);
    ctx.add(FindingCode::value_out_of_range, offset, [&] {
      return cat({spec.name, " ", fmt_number(v, d), spec.unit.empty() ? "" : " ", spec.unit,
                  " outside [", fmt_number(spec.min, d), ", ", fmt_number(spec.max, d), "]"});
    });
  }
  return {};
}

// Each field of `form` on the frame's data: decoded into ctx.out with
// detail, else validated and dropped; then its records, if it has them
// (FormSpec::record: as many as the count says and the data holds, a count
// that does not match the data a data-length at the count).
void check_fields(Ctx& ctx, const FormSpec& form, const Frame& frame);
// Judges a planned form without detail; false (having added nothing) when
// a byte of the data is outside 0-9 A-F, which check_fields must see.
bool judge_planned(Ctx& ctx, const FormPlan& plan, const Frame& frame);

}  // namespace top::detail
