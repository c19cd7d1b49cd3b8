// Field values back into the data of a form, and example data.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "numbers.hpp"
#include "top/decode.hpp"

namespace top {

using detail::decimals_of;
using detail::fmt_number;

namespace {

bool put_hex(std::int64_t v, std::size_t width, bool is_signed, std::string& out) {
  if (width == 0 || width > 15) return false;
  unsigned bits = static_cast<unsigned>(width) * 4;
  std::int64_t lo = is_signed ? -(static_cast<std::int64_t>(1) << (bits - 1)) : 0;
  std::int64_t hi = is_signed ? (static_cast<std::int64_t>(1) << (bits - 1)) - 1
                              : (static_cast<std::int64_t>(1) << bits) - 1;
  if (v < lo || v > hi) return false;
  std::uint64_t u = static_cast<std::uint64_t>(v) & ((static_cast<std::uint64_t>(1) << bits) - 1);
  char b[24];
  std::snprintf(b, sizeof b, "%0*llX", static_cast<int>(width), static_cast<unsigned long long>(u));
  out += b;
  return true;
}

// One field's value appended to `out`; false when it does not fit.
bool encode_field(const FieldSpec& s, const EncodeValue& v, std::string& out) {
  std::size_t w = s.width;
  if (v.use_text &&
      !(s.kind == FieldKind::le_i16 || s.kind == FieldKind::le_u16 || s.kind == FieldKind::le_i32 ||
        s.kind == FieldKind::be_i16 || s.kind == FieldKind::be_u16 || s.kind == FieldKind::u8)) {
    if (w != 0 && v.text.size() != w) return false;
    out.append(v.text);
    return true;
  }
  std::int64_t iv =
      static_cast<std::int64_t>(std::llround(s.scale != 0 ? v.number / s.scale : v.number));
  switch (s.kind) {
    case FieldKind::hex_u:
    case FieldKind::enum_hex:
      if (!put_hex(iv, w, false, out)) return false;
      break;
    case FieldKind::hex_s:
      if (!put_hex(iv, w, true, out)) return false;
      break;
    case FieldKind::dec_u: {
      if (iv < 0 || w == 0 || w > 18) return false;
      char b[32];
      int n = std::snprintf(b, sizeof b, "%0*lld", static_cast<int>(w), static_cast<long long>(iv));
      if (n != static_cast<int>(w)) return false;
      out += b;
      break;
    }
    case FieldKind::enum_char: {
      if (w != 1 && w != 0) return false;
      out += static_cast<char>(static_cast<int>(v.number));
      break;
    }
    case FieldKind::number: {
      std::string t = fmt_number(v.number, decimals_of(s.scale));
      if (w != 0) {
        if (t.size() > w) return false;
        bool neg = !t.empty() && t[0] == '-';
        std::string digits = neg ? t.substr(1) : t;
        std::string pad(w - t.size(), '0');
        t = (neg ? "-" : "") + pad + digits;
      }
      out += t;
      break;
    }
    case FieldKind::le_i16:
    case FieldKind::le_u16:
    case FieldKind::le_i32: {
      std::size_t n = s.kind == FieldKind::le_i32 ? 4 : 2;
      std::int64_t lo = s.kind == FieldKind::le_i16   ? -32768
                        : s.kind == FieldKind::le_u16 ? 0
                                                      : INT32_MIN;
      std::int64_t hi = s.kind == FieldKind::le_i16   ? 32767
                        : s.kind == FieldKind::le_u16 ? 65535
                                                      : INT32_MAX;
      if (iv < lo || iv > hi) return false;
      auto u = static_cast<std::uint32_t>(iv);
      for (std::size_t k = 0; k < n; ++k) out += static_cast<char>((u >> (8 * k)) & 0xFF);
      break;
    }
    case FieldKind::be_i16:
    case FieldKind::be_u16: {
      const bool sign = s.kind == FieldKind::be_i16;
      if (iv < (sign ? -32768 : 0) || iv > (sign ? 32767 : 65535)) return false;
      const auto u = static_cast<std::uint16_t>(iv);
      out += static_cast<char>(u >> 8);
      out += static_cast<char>(u & 0xFF);
      break;
    }
    case FieldKind::u8:
      if (iv < 0 || iv > 255) return false;
      out += static_cast<char>(iv);
      break;
    case FieldKind::text:
    case FieldKind::nmea:
    case FieldKind::raw:
      return false;  // these take text
  }
  return true;
}

}  // namespace

bool encode_fields(const FormSpec& form, std::span<const EncodeValue> values, std::string& out) {
  out.clear();
  if (values.size() < form.fields.size()) return false;
  for (std::size_t i = 0; i < form.fields.size(); ++i)
    if (!encode_field(form.fields[i], values[i], out)) return false;
  // The values past the fields, whole records (the count is the caller's).
  if (form.record.empty()) return true;
  const std::span<const EncodeValue> rest = values.subspan(form.fields.size());
  if (rest.size() % form.record.size() != 0) return false;
  for (std::size_t i = 0; i < rest.size(); ++i)
    if (!encode_field(form.record[i % form.record.size()], rest[i], out)) return false;
  return true;
}

namespace {

// One field's example, mid-range (`count`: the value of a form's record
// count) appended to `out`.
void example_field(const FieldSpec& s, const double* count, std::string& out) {
  std::size_t w = s.width;
  EncodeValue v;
  if (count) {
    v.number = *count;
  } else if (!s.enums.empty() &&
             (s.kind == FieldKind::enum_hex || s.kind == FieldKind::enum_char)) {
    v.number = static_cast<double>(s.enums.back().value);
  } else if (s.min <= s.max) {
    double mid = (s.min + s.max) / 2;
    v.number = s.scale != 0 ? std::round(mid / s.scale) * s.scale : mid;
  }
  std::string part;
  EncodeValue one[1] = {v};
  FormSpec single;
  FieldSpec copy = s;
  single.fields = std::span<const FieldSpec>(&copy, 1);
  switch (s.kind) {
    case FieldKind::text: {
      std::string t = w == 0 ? std::string("192.168.144.108") : std::string(w, 'A');
      out += t;
      return;
    }
    case FieldKind::nmea: {
      // E/W + dddmm.mmmm in 11 chars, N/S + ddmm.mmmm in 10 (Topotek
      // 5.8.1, 5.8.2).
      std::string t = w == 10 ? "N3012.1234" : "E12030.1234";
      if (w != 0) t.resize(w, '0');
      out += t;
      return;
    }
    case FieldKind::raw:
      out += std::string(w, '0');
      return;
    default:
      break;
  }
  if (w == 0 && s.kind != FieldKind::number) {
    // Variable-width numeric: use two digits.
    copy.width = 2;
  }
  if (!encode_fields(single, one, part)) {
    // Fall back to zero, which every numeric field can hold.
    one[0].number = 0;
    if (!encode_fields(single, one, part)) part = std::string(w ? w : 2, '0');
  }
  out += part;
}

}  // namespace

std::string example_data(const FormSpec& form) {
  std::string out;
  // A form with records (the Topotek ODR) gets one.
  const double one_record = 1;
  for (const FieldSpec& s : form.fields)
    example_field(s, !form.record.empty() && &s == &form.fields.back() ? &one_record : nullptr,
                  out);
  if (!form.record.empty())
    for (const FieldSpec& s : form.record) example_field(s, nullptr, out);
  if (out.size() < form.min_length) out.resize(form.min_length, '0');
  return out;
}

}  // namespace top
