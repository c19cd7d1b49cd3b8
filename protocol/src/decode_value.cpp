// A decoded field as text, and the exact decimal behind it.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "numbers.hpp"
#include "top/decode.hpp"
#include "top/detail/decimal.hpp"

namespace top {

using detail::decimal_scale;
using detail::decimals_of;
using detail::fmt_number;
using detail::kPow10;

namespace detail {

bool exact_decimal(const FieldValue& f, std::int64_t& mantissa, int& decimals) noexcept {
  if (!f.spec || !f.valid || f.none) return false;
  if (!is_integer_kind(f.spec->kind)) return false;
  std::int64_t m = 0;
  if (!decimal_scale(f.spec->scale, m, decimals)) return false;
  constexpr std::int64_t kMax = 1'000'000'000'000'000;  // 10^15: 15 digits
  // and the value must be that decimal's double (a FieldValue built by hand
  // may say otherwise): then the two texts agree
  return !__builtin_mul_overflow(f.integer, m, &mantissa) && mantissa > -kMax && mantissa < kMax &&
         static_cast<double>(mantissa) / kPow10[decimals] == f.value;
}

}  // namespace detail

namespace {

// mantissa / 10^decimals with exactly `decimals` digits after the point.
[[gnu::always_inline]] inline void append_fixed(std::string& out, std::int64_t mantissa,
                                                int decimals) {
  char b[32];
  char* e = b + sizeof b;
  char* p = e;
  std::uint64_t u = mantissa < 0 ? 0 - static_cast<std::uint64_t>(mantissa)
                                 : static_cast<std::uint64_t>(mantissa);
  for (int i = 0; i < decimals; ++i) {
    *--p = static_cast<char>('0' + u % 10);
    u /= 10;
  }
  if (decimals > 0) *--p = '.';
  do {
    *--p = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u);
  if (mantissa < 0) *--p = '-';
  out.append(p, static_cast<std::size_t>(e - p));
}

}  // namespace

namespace {

// plain: the value alone (append_plain_value), else as a person reads it.
[[gnu::always_inline]] inline void put_value(const FieldValue& f, std::string& out, bool plain) {
  if (!f.spec) return;
  const FieldSpec& s = *f.spec;
  if (plain && (f.none || !f.valid)) return;
  if (f.none) {
    out += "none (";
    out += f.text;
    out += ')';
    return;
  }
  if (!f.valid) {
    out += '\'';
    out += f.text;
    out += "' (invalid)";
    return;
  }
  auto unit = [&] {
    if (!plain && !s.unit.empty()) {
      out += ' ';
      out += s.unit;
    }
  };
  switch (s.kind) {
    case FieldKind::enum_hex:
    case FieldKind::enum_char: {
      // the code: the character(s), or the value as hex digits of the
      // field's width (printf's "%0*llX")
      char b[24];
      std::string_view code = f.text;
      if (s.kind == FieldKind::enum_hex) {
        int n = 0;
        if (f.length <= 16) {
          static constexpr char kDigits[] = "0123456789ABCDEF";
          const auto u = static_cast<unsigned long long>(f.integer);
          const int w = static_cast<int>(f.length);
          int digits = 1;  // printf widens the field for a value that needs more digits
          while (digits < 16 && (u >> (4 * digits)) != 0) ++digits;
          n = std::max(w, digits);
          for (int i = 0; i < n; ++i) b[i] = kDigits[(u >> (4 * (n - 1 - i))) & 0xF];
        } else {
          n = std::snprintf(b, sizeof b, "%0*llX", static_cast<int>(f.length),
                            static_cast<unsigned long long>(f.integer));
          n = std::clamp(n, 0, static_cast<int>(sizeof b) - 1);
        }
        code = std::string_view(b, static_cast<std::size_t>(n));
      }
      if (plain) {
        out += f.enum_name.empty() ? code : f.enum_name;
      } else if (!f.enum_name.empty()) {
        out += f.enum_name;
        out += " (";
        out += code;
        out += ')';
      } else {
        out += code;
        out += " (undocumented)";
      }
      return;
    }
    case FieldKind::text:
      out += f.text;
      return;
    case FieldKind::raw:
      // printable bytes as they are; binary ones (the Topotek ODZ) as hex
      // pairs, so that no output carries a control byte
      if (detail::all_printable(f.text)) {
        out += f.text;
      } else {
        static constexpr char kDigits[] = "0123456789ABCDEF";
        for (std::size_t i = 0; i < f.text.size(); ++i) {
          const auto b = static_cast<unsigned char>(f.text[i]);
          if (i) out += ' ';
          out += kDigits[b >> 4];
          out += kDigits[b & 0x0F];
        }
      }
      return;
    case FieldKind::nmea:
      out += fmt_number(f.value, 7);
      if (plain) return;
      unit();
      out += " (";
      out += f.text;
      out += ')';
      return;
    case FieldKind::number:
      out += f.text;
      unit();
      return;
    default: {
      std::int64_t mantissa = 0;
      int decimals = 0;
      if (detail::exact_decimal(f, mantissa, decimals))
        append_fixed(out, mantissa, decimals);  // the text printf would give, without it
      else
        out += fmt_number(f.value, decimals_of(s.scale));
      unit();
      if (!plain && !f.enum_name.empty()) {
        out += " (";
        out += f.enum_name;
        out += ')';
      }
      return;
    }
  }
}

}  // namespace

void append_key(const FieldValue& f, std::string& out) {
  out += f.name();
  if (f.record == 0) return;
  out += '[';
  out += std::to_string(f.record);
  out += ']';
}

std::string field_key(const FieldValue& f) {
  std::string s;
  append_key(f, s);
  return s;
}

void append_value(const FieldValue& f, std::string& out) { put_value(f, out, false); }
void append_plain_value(const FieldValue& f, std::string& out) { put_value(f, out, true); }

std::string format_value(const FieldValue& f) {
  std::string s;
  append_value(f, s);
  return s;
}

std::string Decoded::summary() const {
  std::string s;
  append_summary(s);
  return s;
}

void Decoded::append_summary(std::string& out) const {
  if (form && !form->none.empty() && !fields.empty() && fields.front().none &&
      !form->note.empty()) {
    out.append("none (").append(form->note).append(")");
    return;
  }
  const std::size_t start = out.size();
  for (const FieldValue& f : fields) {
    if (out.size() != start) out += ", ";
    append_key(f, out);
    out += ' ';
    append_value(f, out);
  }
}

}  // namespace top
