// A form's data, field by field: each field decoded (with detail) or
// judged (without), the records of a form that has them (the Topotek ODR),
// and the verdict of a planned form without detail (decode_plan.hpp).
#include <array>
#include <climits>
#include <cmath>
#include <cstring>

#include "chars.hpp"
#include "decode_ctx.hpp"
#include "decode_plan.hpp"
#include "field_read.hpp"
#include "numbers.hpp"

namespace top::detail {

namespace {

void decode_field(Ctx& ctx, const FieldSpec& spec, std::string_view bytes, std::uint32_t offset,
                  FieldValue& fv) {
  fv.spec = &spec;
  fv.offset = offset;
  fv.length = static_cast<std::uint32_t>(bytes.size());
  if (!spec.none.empty() && bytes == spec.none) {
    fv.none = true;
    fv.valid = true;
    ctx.keep(fv, bytes);
    return;
  }
  // "<name>: " + why, in up to three pieces
  auto bad = [&](std::string_view why, std::string_view more = {}, std::string_view end = {}) {
    fv.valid = false;
    ctx.keep(fv, bytes);
    ctx.add(FindingCode::bad_field, offset, [&] { return cat({spec.name, ": ", why, more, end}); });
  };
  switch (spec.kind) {
    case FieldKind::hex_u:
    case FieldKind::hex_s:
    case FieldKind::enum_hex: {
      if (bytes.empty() || bytes.size() > 15) return bad("no hex digits");
      std::uint64_t v = 0;
      bool lower = false;
      for (char c : bytes) {
        int h = hex_value(c);
        if (h < 0) return bad("'", bytes, "' is not hex");
        lower |= is_lower_hex(c);
        v = v * 16 + static_cast<unsigned>(h);
      }
      if (lower && !ctx.lowercase_reported) {
        ctx.lowercase_reported = true;
        ctx.add(FindingCode::lowercase_hex, offset, [&] {
          return cat({spec.name, ": hex digits '", bytes, "' in lowercase"});
        });
      }
      std::int64_t iv = static_cast<std::int64_t>(v);
      if (spec.kind == FieldKind::hex_s) {
        unsigned bits = static_cast<unsigned>(bytes.size()) * 4;
        if (bits < 64 && (v >> (bits - 1)) & 1u)
          iv = static_cast<std::int64_t>(v) - (static_cast<std::int64_t>(1) << bits);
      }
      fv.integer = iv;
      fv.value = scaled(iv, spec.scale);
      fv.valid = true;
      break;
    }
    case FieldKind::dec_u: {
      std::int64_t v = 0;
      if (bytes.empty()) return bad("no digits");
      for (char c : bytes) {
        if (c < '0' || c > '9') return bad("'", bytes, "' is not decimal");
        v = v * 10 + (c - '0');
      }
      fv.integer = v;
      fv.value = scaled(v, spec.scale);
      fv.valid = true;
      break;
    }
    case FieldKind::enum_char: {
      if (bytes.empty()) return bad("empty");
      fv.integer = static_cast<unsigned char>(bytes[0]);
      fv.value = static_cast<double>(fv.integer);
      ctx.keep(fv, bytes);
      fv.valid = true;
      break;
    }
    case FieldKind::text: {
      if (!detail::all_printable(bytes)) return bad("non-printable bytes in text");
      ctx.keep(fv, bytes);
      fv.valid = true;
      return;
    }
    case FieldKind::number: {
      double v = 0;
      std::string_view t = bytes;
      while (!t.empty() && t.front() == ' ') t.remove_prefix(1);
      if (!detail::parse_number(t, v)) return bad("'", bytes, "' is not a number");
      fv.value = v * spec.scale;
      fv.integer = static_cast<std::int64_t>(v);
      ctx.keep(fv, bytes);
      fv.valid = true;
      break;
    }
    case FieldKind::le_i16:
    case FieldKind::le_u16:
    case FieldKind::le_i32:
    case FieldKind::be_i16:
    case FieldKind::be_u16:
    case FieldKind::u8: {
      const std::size_t w = spec.kind == FieldKind::le_i32 ? 4 : spec.kind == FieldKind::u8 ? 1 : 2;
      if (bytes.size() != w) return bad("needs ", std::to_string(w), " bytes");
      const std::int64_t iv = detail::binary_int(spec.kind, bytes);
      fv.integer = iv;
      fv.value = scaled(iv, spec.scale);
      fv.valid = true;
      break;
    }
    case FieldKind::nmea: {
      if (!detail::decode_nmea(bytes, fv.value, bad)) return;
      ctx.keep(fv, bytes);
      fv.valid = true;
      break;
    }
    case FieldKind::raw: {
      ctx.keep(fv, bytes);
      fv.valid = true;
      return;
    }
  }
  fv.enum_name = judge(ctx, spec, bytes, offset, fv.integer, [&] { return fv.value; });
}

// Without detail: the findings decode_field gives, without building a value.
// The hex kinds whose digits are all uppercase hex (most fields) are judged
// here; anything else goes through decode_field into `scratch`.
void check_field(Ctx& ctx, const FieldSpec& spec, std::string_view bytes, std::uint32_t offset,
                 FieldValue& scratch) {
  const bool hex = spec.kind == FieldKind::hex_u || spec.kind == FieldKind::hex_s ||
                   spec.kind == FieldKind::enum_hex;
  if (hex && !bytes.empty() && bytes.size() <= 15 && (spec.none.empty() || bytes != spec.none)) {
    std::uint64_t v = 0;
    int digits = 0;  // negative once a byte is no hex digit
    bool lower = false;
    for (char c : bytes) {
      const int h = hex_value(c);
      digits |= h;
      lower |= is_lower_hex(c);
      v = v * 16 + static_cast<unsigned>(h & 0x0F);
    }
    if (digits >= 0 && !lower) {
      std::int64_t iv = static_cast<std::int64_t>(v);
      const unsigned bits = static_cast<unsigned>(bytes.size()) * 4;  // at most 60
      if (spec.kind == FieldKind::hex_s && (v >> (bits - 1)) & 1u)
        iv -= static_cast<std::int64_t>(1) << bits;
      judge(ctx, spec, bytes, offset, iv, [&] { return scaled(iv, spec.scale); });
      return;
    }
  }
  scratch.valid = scratch.none = false;
  scratch.integer = 0;
  scratch.value = 0;
  scratch.enum_name = {};
  decode_field(ctx, spec, bytes, offset, scratch);
}

// One field on `bytes` at frame offset `at`: decoded into the next field
// with detail (of record `record`, 0 for the form's own), else validated.
void check_one(Ctx& ctx, const FieldSpec& fs, std::string_view bytes, std::uint32_t at,
               std::uint16_t record, FieldValue& scratch) {
  if (ctx.detail) {
    FieldValue& fv = ctx.out.fields.emplace_back();
    decode_field(ctx, fs, bytes, at, fv);
    fv.record = record;
  } else {
    check_field(ctx, fs, bytes, at, scratch);
  }
}

// The records of a form that has them (FormSpec::record), from `pos` on:
// as many as the count field (the form's last, at `count_at` in the data)
// says and the data holds; a count the data does not match is a
// data-length finding at the count (count 0 with no bytes after it is
// none).
void check_records(Ctx& ctx, const FormSpec& form, const Frame& frame, std::size_t count_at,
                   std::size_t pos, FieldValue& scratch) {
  const std::string_view data = frame.data();
  const FieldSpec& cs = form.fields.back();
  Decoded quiet;  // the count's findings are the fields' own, given already
  Ctx q{frame, quiet, false};
  FieldValue count;
  decode_field(q, cs, data.substr(count_at, pos - count_at), 0, count);
  if (!count.valid || count.none || count.integer < 0) return;
  std::size_t width = 0;
  for (const FieldSpec& r : form.record) width += r.width;
  if (width == 0) return;
  const std::size_t left = data.size() - pos, whole = left / width;
  const auto n = static_cast<std::uint64_t>(count.integer);
  if (n * width != left)
    ctx.add(FindingCode::data_length, static_cast<std::uint32_t>(frame.data_offset + count_at),
            [&] {
              return cat({cs.name, " ", std::to_string(n), ": ", std::to_string(n),
                          " record(s) of ", std::to_string(width), " byte(s) need ",
                          std::to_string(n * width), ", ", std::to_string(left), " follow"});
            });
  const std::size_t records = n < whole ? static_cast<std::size_t>(n) : whole;
  for (std::size_t i = 0; i < records; ++i)
    for (const FieldSpec& r : form.record) {
      check_one(ctx, r, data.substr(pos, r.width),
                static_cast<std::uint32_t>(frame.data_offset + pos),
                static_cast<std::uint16_t>(i + 1), scratch);
      pos += r.width;
    }
}

}  // namespace

// Judges a planned form; false (having added nothing) when a byte of the
// data is outside 0-9 A-F, which check_field must see.
bool judge_planned(Ctx& ctx, const FormPlan& plan, const Frame& frame) {
  const char* data = frame.raw.data() + frame.data_offset;
  if (!hex_lanes(word_before(data + plan.head), plan.head_lanes) ||
      !hex_lanes(word_before(data + plan.width), plan.tail_lanes))
    return false;
  for (const FieldCheck& c : plan.valued) {
    const std::uint64_t x = word_before(data + c.end) & c.bytes;  // the chars, at the top
    const std::uint64_t nibbles = (x & (kOnes * 0x0F)) + (lanes_in(x, 'A', 'F') >> 7) * 9;
    // the last char lowest, then pairs, quads and eights of nibbles joined
    std::uint64_t v = __builtin_bswap64(nibbles);
    v = (v | (v >> 4)) & 0x00FF00FF00FF00FFull;
    v = (v | (v >> 8)) & 0x0000FFFF0000FFFFull;
    v = (v | (v >> 16)) & 0x00000000FFFFFFFFull;
    const auto iv = static_cast<std::int64_t>(v) -
                    static_cast<std::int64_t>((v & c.sign_bit) ? c.sign_bit << 1 : 0);
    const bool labelled = c.labels & (iv >= 0) & (iv < 64) & ((c.label_bits >> (iv & 63)) & 1u);
    if (!labelled && (c.enum_only || iv < c.lo || iv > c.hi))
      ctx.add(FindingCode::value_out_of_range, frame.data_offset + c.end - c.bits / 4,
              [] { return std::string(); });
  }
  return true;
}

// Each field of `form` on the frame's data: decoded with detail, else
// validated and dropped; then its records, if it has them.
void check_fields(Ctx& ctx, const FormSpec& form, const Frame& frame) {
  std::string_view data = frame.data();
  std::size_t pos = 0, last = 0;
  std::size_t done = 0;  // fields decoded
  FieldValue scratch;
  for (const FieldSpec& fs : form.fields) {
    if (pos >= data.size() && fs.width != 0) break;
    std::size_t w = fs.width == 0 ? data.size() - pos : fs.width;
    if (pos + w > data.size()) {
      ctx.add(FindingCode::data_length, static_cast<std::uint32_t>(frame.data_offset + pos), [&] {
        return cat({fs.name, " needs ", std::to_string(w), " byte(s), ",
                    std::to_string(data.size() - pos), " left"});
      });
      break;
    }
    const auto at = static_cast<std::uint32_t>(frame.data_offset + pos);
    check_one(ctx, fs, data.substr(pos, w), at, 0, scratch);
    last = pos;
    pos += w;
    ++done;
  }
  if (!form.record.empty() && done == form.fields.size() && done > 0)
    check_records(ctx, form, frame, last, pos, scratch);
}

}  // namespace top::detail
