#include "decode_plan.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <span>

#include "numbers.hpp"

namespace top::detail {

namespace {

// The integers whose scaled value judge() finds inside [min, max]: scaled()
// rises with the integer, so they are one interval, found by stepping from
// the nearest guess. False when the range cannot be planned.
bool plan_range(const FieldSpec& s, std::int64_t& lo, std::int64_t& hi) {
  if (!(s.scale > 0) || !std::isfinite(s.scale) || !std::isfinite(s.min) || !std::isfinite(s.max) ||
      std::fabs(s.min / s.scale) > 1e12 || std::fabs(s.max / s.scale) > 1e12)
    return false;
  auto above_min = [&](std::int64_t i) { return !(scaled(i, s.scale) < s.min - 1e-9); };
  auto below_max = [&](std::int64_t i) { return !(scaled(i, s.scale) > s.max + 1e-9); };
  lo = std::llround(s.min / s.scale);
  hi = std::llround(s.max / s.scale);
  for (int step = 0; step < 64 && above_min(lo - 1); ++step) --lo;
  for (int step = 0; step < 64 && !above_min(lo); ++step) ++lo;
  for (int step = 0; step < 64 && below_max(hi + 1); ++step) ++hi;
  for (int step = 0; step < 64 && !below_max(hi); ++step) --hi;
  return above_min(lo) && !above_min(lo - 1) && below_max(hi) && !below_max(hi + 1);
}

// Plans a field of a fast form; false when the form cannot be planned.
bool plan_field(const FieldSpec& s, std::uint32_t at, FormPlan& p) {
  if ((s.kind != FieldKind::hex_u && s.kind != FieldKind::hex_s && s.kind != FieldKind::enum_hex) ||
      s.width == 0 || s.width > 8 || !s.none.empty())
    return false;
  FieldCheck c;
  c.end = at + s.width;
  c.bits = 4u * s.width;
  c.bytes = top_bytes(s.width);
  c.sign_bit = s.kind == FieldKind::hex_s ? std::uint64_t{1} << (c.bits - 1) : 0;
  if (!s.enums.empty()) {
    for (const EnumValue& e : s.enums) {
      if (e.value < 0 || e.value > 63) return false;
      c.label_bits |= std::uint64_t{1} << e.value;
    }
    c.labels = true;
    c.enum_only = s.kind == FieldKind::enum_hex;
  }
  if (s.min <= s.max && !plan_range(s, c.lo, c.hi)) return false;
  if (c.labels || s.min <= s.max) p.valued.push_back(c);
  return true;
}

FormPlan plan_form(const FormSpec& f) {
  FormPlan p;
  p.fast = std::endian::native == std::endian::little && f.none.empty() && f.record.empty();
  for (const FieldSpec& s : f.fields) {
    p.fast = p.fast && plan_field(s, p.width, p);
    p.width += s.width;
  }
  p.fast = p.fast && p.width <= 16;
  if (!p.fast) return p;
  const unsigned head = std::min(p.width, 8u), tail = p.width > 8 ? p.width - 8 : p.width;
  p.head = head;
  p.head_lanes = top_lanes(head);
  p.tail_lanes = top_lanes(tail);
  return p;
}

}  // namespace

const FormPlan& plan_of(const CommandSpec& cmd, const FormSpec& form) {
  using Plans = std::vector<std::vector<FormPlan>>;  // [command][form]
  struct Dialects {
    std::array<std::span<const CommandSpec>, 2> table;  // commands(): SkyDroid, Topotek
    std::array<Plans, 2> plans;
  };
  static const Dialects kAll = [] {
    Dialects all;
    for (std::size_t d = 0; d < 2; ++d) {
      all.table[d] = commands(d == 0 ? Dialect::skydroid : Dialect::topotek);
      for (const CommandSpec& c : all.table[d]) {
        auto& forms = all.plans[d].emplace_back();
        for (const FormSpec& f : c.forms) forms.push_back(plan_form(f));
      }
    }
    return all;
  }();
  static const FormPlan kNone;
  const std::size_t d = cmd.dialect == Dialect::topotek ? 1 : 0;
  const std::span<const CommandSpec> table = kAll.table[d];
  const auto ci = static_cast<std::size_t>(&cmd - table.data());
  const auto fi = static_cast<std::size_t>(&form - cmd.forms.data());
  if (table.empty() || &cmd < table.data() || ci >= table.size() || fi >= cmd.forms.size())
    return kNone;
  return kAll.plans[d][ci][fi];
}

}  // namespace top::detail
