#include "top/decode.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "chars.hpp"
#include "top/device.hpp"
#include "top/dialect.hpp"

namespace top {

using detail::hex_value;
using detail::is_lower_hex;

namespace {

bool role_fits(Role form, Role frame) noexcept {
  return form == Role::any || frame == Role::any || form == frame;
}

int decimals_of(double scale) noexcept {
  if (scale <= 0) return 0;
  int d = 0;
  double s = scale;
  while (d < 9 && std::fabs(s - std::round(s)) > 1e-9) {
    s *= 10;
    ++d;
  }
  return d;
}

// printf("%.*f") (std::to_chars promises the same text, several times
// faster); past 64 characters (a huge decimal number field) snprintf sizes it.
constexpr double kPow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

// A scale as m / 10^d with m an integer (0.01 -> 1/10^2, 0.5 -> 5/10^1);
// false when it is no decimal fraction (1/3) or needs more than 9 decimals.
bool decimal_scale(double scale, std::int64_t& m, int& d) noexcept {
  // the scales of the catalog, without the search below
  struct Known {
    double scale;
    std::int64_t m;
    int d;
  };
  static constexpr Known kKnown[] = {{1.0, 1, 0}, {0.01, 1, 2}, {0.1, 1, 1},  {0.001, 1, 3},
                                     {0.5, 5, 1}, {1e-7, 1, 7}, {0.05, 5, 2}, {0.0001, 1, 4}};
  for (const Known& k : kKnown)
    if (scale == k.scale) {
      m = k.m;
      d = k.d;
      return true;
    }
  d = decimals_of(scale);
  const double x = scale * kPow10[d];
  if (!(scale > 0) || std::fabs(x - std::round(x)) > 1e-9 || x > 1e9) return false;
  m = std::llround(x);
  return true;
}

// integer * scale, correctly rounded when the scale is a decimal fraction:
// 0.01 * -295 gives -2.95 rather than -2.9500000000000002.
double scaled_slow(std::int64_t iv, double scale) noexcept;

inline double scaled(std::int64_t iv, double scale) noexcept {
  constexpr std::int64_t kExact = std::int64_t{1} << 53;  // integers a double holds
  if (iv > -kExact && iv < kExact) {                      // the catalog's usual scales, inline
    if (scale == 1.0) return static_cast<double>(iv);
    if (scale == 0.01) return static_cast<double>(iv) / 100.0;
    if (scale == 0.1) return static_cast<double>(iv) / 10.0;
  }
  return scaled_slow(iv, scale);
}

double scaled_slow(std::int64_t iv, double scale) noexcept {
  std::int64_t m = 0, mant = 0;
  int d = 0;
  if (decimal_scale(scale, m, d) && !__builtin_mul_overflow(iv, m, &mant) &&
      mant > -(std::int64_t{1} << 53) && mant < (std::int64_t{1} << 53))
    return static_cast<double>(mant) / kPow10[d];
  return static_cast<double>(iv) * scale;
}

std::string fmt_number(double v, int decimals) {
  char b[64];
  auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, decimals);
  if (r.ec == std::errc()) return std::string(b, r.ptr);
  const int n = std::snprintf(nullptr, 0, "%.*f", decimals, v);
  if (n <= 0) return std::string();
  std::string s(static_cast<std::size_t>(n) + 1, '\0');  // with snprintf's terminator
  const int written = std::snprintf(s.data(), s.size(), "%.*f", decimals, v);
  s.resize(static_cast<std::size_t>(std::clamp(written, 0, n)));
  return s;
}

const EnumValue* find_enum(std::span<const EnumValue> e, std::int64_t v) noexcept {
  for (const EnumValue& x : e)
    if (x.value == v) return &x;
  return nullptr;
}

bool all_printable(std::string_view s) noexcept {
  for (unsigned char c : s)
    if (c < 0x20 || c >= 0x7F) return false;
  return true;
}

// Parses "[-+]digits[.digits]"; false on anything else.
bool parse_number(std::string_view s, double& out) noexcept {
  if (s.empty()) return false;
  std::size_t i = 0;
  bool neg = false;
  if (s[0] == '-' || s[0] == '+') {
    neg = s[0] == '-';
    i = 1;
  }
  double v = 0, frac = 0.1;
  bool digits = false, point = false;
  for (; i < s.size(); ++i) {
    char c = s[i];
    if (c >= '0' && c <= '9') {
      digits = true;
      if (point) {
        v += (c - '0') * frac;
        frac /= 10;
      } else {
        v = v * 10 + (c - '0');
      }
    } else if (c == '.' && !point) {
      point = true;
    } else {
      return false;
    }
  }
  if (!digits) return false;
  out = neg ? -v : v;
  return true;
}

struct Ctx {
  const Frame& frame;
  Decoded& out;
  bool detail = true;  // DecodeOptions::detail
  bool lowercase_reported = false;
  void add(FindingCode code, std::uint32_t offset, std::string msg) {
    out.findings.push_back(make_finding(code, offset, detail ? std::move(msg) : std::string()));
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
      ctx.add(FindingCode::value_out_of_range, offset,
              std::string(spec.name) + ": '" + std::string(bytes) + "' is not a documented value");
      return {};
    }
  }
  if (spec.min > spec.max) return {};
  const double v = value();
  if (v < spec.min - 1e-9 || v > spec.max + 1e-9) {
    int d = decimals_of(spec.scale);
    ctx.add(FindingCode::value_out_of_range, offset,
            std::string(spec.name) + " " + fmt_number(v, d) + (spec.unit.empty() ? "" : " ") +
                std::string(spec.unit) + " outside [" + fmt_number(spec.min, d) + ", " +
                fmt_number(spec.max, d) + "]");
  }
  return {};
}

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
  auto bad = [&](std::string why) {
    fv.valid = false;
    ctx.keep(fv, bytes);
    ctx.add(FindingCode::bad_field, offset, std::string(spec.name) + ": " + why);
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
        if (h < 0) return bad("'" + std::string(bytes) + "' is not hex");
        lower |= is_lower_hex(c);
        v = v * 16 + static_cast<unsigned>(h);
      }
      if (lower && !ctx.lowercase_reported) {
        ctx.lowercase_reported = true;
        ctx.add(FindingCode::lowercase_hex, offset,
                std::string(spec.name) + ": hex digits '" + std::string(bytes) + "' in lowercase");
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
        if (c < '0' || c > '9') return bad("'" + std::string(bytes) + "' is not decimal");
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
      if (!all_printable(bytes)) return bad("non-printable bytes in text");
      ctx.keep(fv, bytes);
      fv.valid = true;
      return;
    }
    case FieldKind::number: {
      double v = 0;
      std::string_view t = bytes;
      while (!t.empty() && t.front() == ' ') t.remove_prefix(1);
      if (!parse_number(t, v)) return bad("'" + std::string(bytes) + "' is not a number");
      fv.value = v * spec.scale;
      fv.integer = static_cast<std::int64_t>(v);
      ctx.keep(fv, bytes);
      fv.valid = true;
      break;
    }
    case FieldKind::le_i16:
    case FieldKind::le_u16:
    case FieldKind::le_i32: {
      std::size_t w = spec.kind == FieldKind::le_i32 ? 4 : 2;
      if (bytes.size() != w) return bad("needs " + std::to_string(w) + " bytes");
      std::uint32_t u = 0;
      for (std::size_t i = 0; i < w; ++i)
        u |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << (8 * i);
      std::int64_t iv = 0;
      if (spec.kind == FieldKind::le_i16)
        iv = static_cast<std::int16_t>(static_cast<std::uint16_t>(u));
      else if (spec.kind == FieldKind::le_u16)
        iv = static_cast<std::uint16_t>(u);
      else
        iv = static_cast<std::int32_t>(u);
      fv.integer = iv;
      fv.value = scaled(iv, spec.scale);
      fv.valid = true;
      break;
    }
    case FieldKind::nmea: {
      // "E" + dddmm.mmmm or "N" + ddmm.mmmm (as in $GPGGA).
      if (bytes.size() < 2) return bad("too short for a hemisphere and a coordinate");
      char hemi = bytes[0];
      if (hemi != 'E' && hemi != 'W' && hemi != 'N' && hemi != 'S')
        return bad(std::string("hemisphere '") + hemi + "' is not N S E W");
      double raw = 0;
      if (!parse_number(bytes.substr(1), raw) || raw < 0)
        return bad("'" + std::string(bytes.substr(1)) + "' is not dddmm.mmmm");
      double deg = std::floor(raw / 100.0);
      double minutes = raw - deg * 100.0;
      double v = deg + minutes / 60.0;
      if (hemi == 'W' || hemi == 'S') v = -v;
      fv.value = v;
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

// --- the verdict without detail, planned per form ---------------------------
//
// Most forms are a few hex fields of 1-8 chars, at most 16 chars in all.
// Without detail such a form is judged with few branches and none on its
// digits: the whole data is checked for 0-9 A-F as two eight-byte words,
// and only the fields that have a range or labels are converted (lane-wise,
// from one word each) and compared with integer bounds worked out once from
// the field's scaled range. Frames of every identifier arrive interleaved, so
// the per-char loops, scale tests and comparisons of decode_field mispredict
// often. Any byte outside 0-9 A-F sends the whole form back to check_field,
// which gives the exact findings.

constexpr std::uint64_t kOnes = 0x0101010101010101ull, kTops = 0x8080808080808080ull;

// The top `n` (0-8; no more) bytes of a word as their top bits, and as
// whole bytes.
constexpr std::uint64_t top_lanes(unsigned n) noexcept { return n ? kTops << (8 * (8 - n)) : 0; }
constexpr std::uint64_t top_bytes(unsigned n) noexcept { return (top_lanes(n) >> 7) * 0xFF; }

// A field that has a range or labels.
struct FieldCheck {
  std::uint32_t end = 0;                        // offset in the data just past the field
  std::uint32_t bits = 0;                       // 4 per char
  std::uint64_t bytes = 0;                      // the field's chars in the word that ends with it
  std::uint64_t sign_bit = 0;                   // hex_s: the top bit of the value (0: unsigned)
  std::uint64_t label_bits = 0;                 // which values 0-63 have a label
  bool labels = false;                          // a value with a label is exempt from the range
  bool enum_only = false;                       // enum_hex: a value without a label is out of range
  std::int64_t lo = INT64_MIN, hi = INT64_MAX;  // the integers inside the range
};

struct FormPlan {
  bool fast = false;        // every field is planned and the form has no "none" data
  std::uint32_t width = 0;  // the data length the fields cover (at most 16)
  // The data is checked as the words that end at `head` and at `width`.
  std::uint32_t head = 0;
  std::uint64_t head_lanes = 0, tail_lanes = 0;
  std::vector<FieldCheck> valued;  // the fields with a range or labels
};

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
  p.fast = std::endian::native == std::endian::little && f.none.empty();
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

// The plan of a form of a catalog command (commands() holds every command a
// decode can find); an empty plan for anything else.
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

// The eight bytes that end at p (the frame's own: every header puts at least
// eight bytes before the data).
std::uint64_t word_before(const char* p) noexcept {
  std::uint64_t x;
  std::memcpy(&x, p - 8, 8);
  return x;
}

// The lanes of x (bytes below 0x80) whose byte lies in [lo, hi], as their
// top bit.
std::uint64_t lanes_in(std::uint64_t x, unsigned lo, unsigned hi) noexcept {
  return (x + kOnes * (0x80 - lo)) & ~(x + kOnes * (0x7F - hi)) & kTops;
}

// True when every lane of `lanes` holds 0-9 or A-F.
bool hex_lanes(std::uint64_t x, std::uint64_t lanes) noexcept {
  return ((lanes_in(x, '0', '9') | lanes_in(x, 'A', 'F')) & lanes) == lanes && (x & lanes) == 0;
}

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
              std::string());
  }
  return true;
}

// What a frame's dialect, role, identifier, header, lengths and control
// decide: the command, the form and their findings, in `out` (out.form stays
// null when no form applies: the decode ends there).
void decode_shape(Ctx& ctx, const Frame& frame, const DecodeOptions& opts, Dialect d,
                  Decoded& out) {
  const std::string_view ident = frame.ident_view();
  const auto ident_at =
      static_cast<std::uint32_t>(frame.header == Header::tmp_quirk ? 6 : frame.data_offset - 3);
  const CommandSpec* cmd = d == Dialect::unknown ? find_any(ident) : find_command(d, ident);
  if (cmd && d == Dialect::unknown) d = cmd->dialect;
  out.dialect = d;
  out.command = cmd;

  if (frame.header == Header::fixed && frame.declared_length != 2) {
    bool g_class = cmd && cmd->address == 'G' && d == Dialect::skydroid;
    // Every SkyDroid GAC stream frame has this finding: its 32 possible
    // messages (length 0-F, G class or not) are built once.
    auto message = [](std::uint32_t length, bool g) {
      return "#TP frame with length " + std::to_string(length) + " (the fixed header implies 2)" +
             (g ? "; SkyDroid puts every G-class command under #TP" : "");
    };
    static const std::array<std::string, 32> kMessages = [&] {
      std::array<std::string, 32> m;
      for (std::uint32_t i = 0; i < m.size(); ++i) m[i] = message(i % 16, i >= 16);
      return m;
    }();
    Finding& f = out.findings.emplace_back();
    f.code = FindingCode::tp_length;
    f.severity = g_class ? Severity::info : default_severity(FindingCode::tp_length);
    f.offset = 5;
    if (ctx.detail)
      f.message = frame.declared_length < 16  // two-digit lengths (TMP quirk) go past F
                      ? kMessages[frame.declared_length + (g_class ? 16 : 0)]
                      : message(frame.declared_length, g_class);
  }
  if (d == Dialect::skydroid && (frame.header == Header::ext8 || frame.header == Header::ext16))
    ctx.add(FindingCode::ext_header_skydroid, 0,
            std::string(to_string(frame.header)) +
                " is a Topotek extended header; SkyDroid defines only #TP/#tp");

  if (!cmd) {
    ctx.add(FindingCode::unknown_ident, ident_at,
            "identifier " + std::string(ident) + " is not in the " +
                std::string(d == Dialect::unknown ? "TOP" : to_string(d)) + " catalog");
    return;
  }
  if (opts.model != Model::unknown && !cmd->supports(opts.model)) {
    // Not in the document for the model: a warning when field evidence says
    // the firmware takes it anyway (device.hpp), an error when nothing does.
    const FieldSupport* fs = field_supported(d, opts.model, ident, std::nullopt);
    ctx.add(FindingCode::unsupported_on_model, ident_at,
            std::string(ident) + " (" + std::string(cmd->section) + ") is not listed for " +
                std::string(to_string(opts.model)) +
                (fs ? "; field: " + std::string(fs->evidence) : std::string()));
    Finding& x = out.findings.back();
    x.severity = fs ? Severity::warning : Severity::error;
    if (fs) x.quirk = fs->evidence;
  }
  if (ident == "ERE")
    ctx.add(FindingCode::error_reply, ident_at,
            std::string("the device rejected a command as invalid (") + frame.src + " to " +
                frame.dst + ")");

  const std::size_t len = frame.data_length;
  const FormSpec* form = nullptr;
  bool swapped = false, control_known = false;
  for (const FormSpec& f : cmd->forms) {
    if (frame.control != 0 && f.control != frame.control) continue;
    control_known = true;
    if (len < f.min_length || len > f.max_length) continue;
    if (role_fits(f.role, out.role)) {
      form = &f;
      break;
    }
    if (!swapped && !form) swapped = true;
  }
  if (!form && swapped) {
    for (const FormSpec& f : cmd->forms) {
      if (frame.control != 0 && f.control != frame.control) continue;
      if (len < f.min_length || len > f.max_length) continue;
      form = &f;
      break;
    }
    if (form)
      ctx.add(FindingCode::unswapped_addresses, 3,
              std::string("laid out as a ") +
                  (form->role == Role::response ? "response" : "request") + " but addressed " +
                  frame.src + " to " + frame.dst);
  }
  if (!control_known) {
    ctx.add(FindingCode::unsupported_control, 6,
            std::string(ident) + " has no '" + std::string(1, frame.control) + "' form in " +
                std::string(cmd->section));
    return;
  }
  if (!form) {
    std::string allowed;
    for (const FormSpec& f : cmd->forms) {
      if (frame.control != 0 && f.control != frame.control) continue;
      if (!allowed.empty()) allowed += ", ";
      allowed += f.min_length == f.max_length
                     ? std::to_string(f.min_length)
                     : std::to_string(f.min_length) + "-" + std::to_string(f.max_length);
    }
    ctx.add(FindingCode::data_length, frame.data_offset,
            std::to_string(len) + " data byte(s); " + std::string(ident) + " '" +
                std::string(1, frame.control ? frame.control : '?') + "' takes " + allowed);
    return;
  }
  out.form = form;
  if (form->role != Role::any && out.role == Role::any) out.role = form->role;
}

// The shape's key for DecodeCache: everything decode_shape reads of the
// frame and the options (messages aside), packed; 0 when a length or the
// control does not fit (those frames are decoded without the cache).
std::uint64_t shape_key(const Frame& f, Dialect d, Role role, Model model) noexcept {
  if (f.declared_length > 0xFF || f.data_length > 0xFF || f.data_offset > 0xF) return 0;
  const std::uint64_t control = f.control == 0     ? 0
                                : f.control == 'r' ? 1
                                : f.control == 'w' ? 2
                                                   : 3;
  if (control == 3) return 0;
  const auto byte = [](char c) { return std::uint64_t{static_cast<unsigned char>(c)}; };
  return std::uint64_t{1} << 63 | static_cast<std::uint64_t>(d) << 54 |
         static_cast<std::uint64_t>(role) << 52 | byte(f.ident[0]) << 44 | byte(f.ident[1]) << 36 |
         byte(f.ident[2]) << 28 | static_cast<std::uint64_t>(f.header) << 25 |
         std::uint64_t{f.declared_length} << 17 | control << 15 |
         std::uint64_t{f.data_length} << 7 | std::uint64_t{f.data_offset} << 3 |
         static_cast<std::uint64_t>(model);
}

}  // namespace

struct DecodeCache::Slot {
  static constexpr std::size_t kFindings = 3;  // a shape with more is not remembered
  std::uint64_t key = 0;
  bool known = false;  // the members below are the key's
  Dialect dialect = Dialect::unknown;
  Role role = Role::any;
  std::uint8_t count = 0;
  const CommandSpec* command = nullptr;
  const FormSpec* form = nullptr;
  const FormPlan* plan = nullptr;
  struct Seen {
    FindingCode code{};
    Severity severity{};
    std::uint32_t offset = 0;
    std::string_view quirk;
  };
  std::array<Seen, kFindings> findings{};
};

static_assert(static_cast<int>(Model::sip) < 8 && static_cast<int>(Header::tmp_quirk) < 8);

DecodeCache::DecodeCache(std::size_t slots) {
  const std::size_t n = std::bit_ceil(std::clamp<std::size_t>(slots, 1, std::size_t{1} << 20));
  slots_ = std::make_unique<Slot[]>(n);
  shift_ = 32 - static_cast<unsigned>(std::countr_zero(n));
}
DecodeCache::~DecodeCache() = default;

DecodeCache::Slot& DecodeCache::slot(std::uint64_t key) noexcept {
  // the top bits of the product: every bit of the key reaches them (the low
  // bits of a product see only the key's low bits, where shapes of different
  // identifiers look alike)
  Slot& s = slots_[static_cast<std::size_t>(((key * 0x9E3779B97F4A7C15ull) >> 32) >> shift_)];
  if (s.key != key) {  // another shape's: forget it all
    ++misses_;
    s.key = key;
    s.known = false;
    s.plan = nullptr;
  }
  return s;
}

namespace {

// The cache's slot for this frame's shape, or null (no cache, or a shape it
// does not key).
DecodeCache::Slot* shape_slot(const DecodeOptions& opts, const Frame& f, Dialect d,
                              Role role) noexcept {
  if (!opts.cache) return nullptr;
  const std::uint64_t key = shape_key(f, d, role, opts.model);
  return key ? &opts.cache->slot(key) : nullptr;
}

void remember(DecodeCache::Slot& s, const Decoded& out) {
  if (out.findings.size() > DecodeCache::Slot::kFindings) return;
  s.dialect = out.dialect;
  s.role = out.role;
  s.command = out.command;
  s.form = out.form;
  s.plan = out.form ? &plan_of(*out.command, *out.form) : nullptr;
  s.count = static_cast<std::uint8_t>(out.findings.size());
  for (std::size_t i = 0; i < out.findings.size(); ++i) {
    const Finding& f = out.findings[i];
    s.findings[i] = {f.code, f.severity, f.offset, f.quirk};
  }
  s.known = true;
}

void replay(const DecodeCache::Slot& s, Decoded& out) {
  out.dialect = s.dialect;
  out.role = s.role;
  out.command = s.command;
  out.form = s.form;
  for (std::size_t i = 0; i < s.count; ++i) {
    const DecodeCache::Slot::Seen& x = s.findings[i];
    out.findings.push_back(Finding{x.code, x.severity, x.offset, std::string(), x.quirk});
  }
}

}  // namespace

void decode(const Frame& frame, const DecodeOptions& opts, Decoded& out) {
  out.fields.clear();
  out.findings.clear();
  out.command = nullptr;
  out.form = nullptr;
  Ctx ctx{frame, out, opts.detail};
  out.role = opts.role != Role::any ? opts.role : role_from_addresses(frame);
  Dialect d = opts.dialect;
  if (d == Dialect::unknown && opts.model != Model::unknown) d = dialect_of(opts.model);
  if (d == Dialect::unknown) d = dialect_from_frame(frame);
  const FormPlan* plan = nullptr;  // the form's, when the shape cache knows it
  if (DecodeCache::Slot* slot = ctx.detail ? nullptr : shape_slot(opts, frame, d, out.role)) {
    if (slot->known) {
      replay(*slot, out);
    } else {
      decode_shape(ctx, frame, opts, d, out);
      remember(*slot, out);  // unless the shape has too many findings
    }
    if (slot->known) plan = slot->plan;
  } else {
    decode_shape(ctx, frame, opts, d, out);
  }
  if (!out.form) return;
  const FormSpec* form = out.form;

  std::string_view data = frame.data();
  std::size_t pos = 0;
  if (!form->none.empty() && data == form->none) {
    if (!ctx.detail) return;
    for (const FieldSpec& fs : form->fields) {
      FieldValue fv;
      fv.spec = &fs;
      fv.offset = static_cast<std::uint32_t>(frame.data_offset + pos);
      fv.length = fs.width ? fs.width : static_cast<std::uint32_t>(data.size() - pos);
      fv.valid = fv.none = true;
      fv.text = std::string(data.substr(pos, fv.length));
      pos += fv.length;
      out.fields.push_back(std::move(fv));
    }
    return;
  }
  if (!ctx.detail && frame.data_offset >= 8) {
    if (!plan) plan = &plan_of(*out.command, *form);
    if (plan->fast && plan->width == data.size() && judge_planned(ctx, *plan, frame)) return;
  }
  FieldValue scratch;  // without detail: each field is validated here, then dropped
  for (const FieldSpec& fs : form->fields) {
    if (pos >= data.size() && fs.width != 0) break;
    std::size_t w = fs.width == 0 ? data.size() - pos : fs.width;
    if (pos + w > data.size()) {
      ctx.add(FindingCode::data_length, static_cast<std::uint32_t>(frame.data_offset + pos),
              std::string(fs.name) + " needs " + std::to_string(w) + " byte(s), " +
                  std::to_string(data.size() - pos) + " left");
      break;
    }
    const auto at = static_cast<std::uint32_t>(frame.data_offset + pos);
    if (ctx.detail)
      decode_field(ctx, fs, data.substr(pos, w), at, out.fields.emplace_back());
    else
      check_field(ctx, fs, data.substr(pos, w), at, scratch);
    pos += w;
  }
  return;
}

Decoded decode(const Frame& frame, const DecodeOptions& opts) {
  Decoded out;
  decode(frame, opts, out);
  return out;
}

bool exact_decimal(const FieldValue& f, std::int64_t& mantissa, int& decimals) noexcept {
  if (!f.spec || !f.valid || f.none) return false;
  switch (f.spec->kind) {
    case FieldKind::hex_u:
    case FieldKind::hex_s:
    case FieldKind::dec_u:
    case FieldKind::le_i16:
    case FieldKind::le_u16:
    case FieldKind::le_i32:
      break;
    default:
      return false;
  }
  std::int64_t m = 0;
  if (!decimal_scale(f.spec->scale, m, decimals)) return false;
  constexpr std::int64_t kMax = 1'000'000'000'000'000;  // 10^15: 15 digits
  // and the value must be that decimal's double (a FieldValue built by hand
  // may say otherwise): then the two texts agree
  return !__builtin_mul_overflow(f.integer, m, &mantissa) && mantissa > -kMax && mantissa < kMax &&
         static_cast<double>(mantissa) / kPow10[decimals] == f.value;
}

namespace {

// mantissa / 10^decimals with exactly `decimals` digits after the point.
void append_fixed(std::string& out, std::int64_t mantissa, int decimals) {
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

void append_value(const FieldValue& f, std::string& out) {
  if (!f.spec) return;
  const FieldSpec& s = *f.spec;
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
    if (!s.unit.empty()) {
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
      if (!f.enum_name.empty()) {
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
    case FieldKind::raw:
      out += f.text;
      return;
    case FieldKind::nmea:
      out += fmt_number(f.value, 7);
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
      if (exact_decimal(f, mantissa, decimals))
        append_fixed(out, mantissa, decimals);  // the text printf would give, without it
      else
        out += fmt_number(f.value, decimals_of(s.scale));
      unit();
      if (!f.enum_name.empty()) {
        out += " (";
        out += f.enum_name;
        out += ')';
      }
      return;
    }
  }
}

std::string format_value(const FieldValue& f) {
  std::string s;
  append_value(f, s);
  return s;
}

std::string Decoded::summary() const {
  std::string s;
  if (form && !form->none.empty() && !fields.empty() && fields.front().none && !form->note.empty())
    return "none (" + std::string(form->note) + ")";
  for (const FieldValue& f : fields) {
    if (!s.empty()) s += ", ";
    s += f.name();
    s += ' ';
    s += format_value(f);
  }
  return s;
}

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

}  // namespace

bool encode_fields(const FormSpec& form, std::span<const EncodeValue> values, std::string& out) {
  out.clear();
  if (values.size() < form.fields.size()) return false;
  for (std::size_t i = 0; i < form.fields.size(); ++i) {
    const FieldSpec& s = form.fields[i];
    const EncodeValue& v = values[i];
    std::size_t w = s.width;
    if (v.use_text && !(s.kind == FieldKind::le_i16 || s.kind == FieldKind::le_u16 ||
                        s.kind == FieldKind::le_i32)) {
      if (w != 0 && v.text.size() != w) return false;
      out.append(v.text);
      continue;
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
        int n =
            std::snprintf(b, sizeof b, "%0*lld", static_cast<int>(w), static_cast<long long>(iv));
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
      case FieldKind::text:
      case FieldKind::nmea:
      case FieldKind::raw:
        return false;  // these take text
    }
  }
  return true;
}

std::string example_data(const FormSpec& form) {
  std::string out;
  for (const FieldSpec& s : form.fields) {
    std::size_t w = s.width;
    EncodeValue v;
    if (!s.enums.empty() && (s.kind == FieldKind::enum_hex || s.kind == FieldKind::enum_char)) {
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
        continue;
      }
      case FieldKind::nmea: {
        std::string t = "E12030.1234";
        if (w != 0) {
          t.resize(w, '0');
        }
        out += t;
        continue;
      }
      case FieldKind::raw:
        out += std::string(w, '0');
        continue;
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
  if (out.size() < form.min_length) out.resize(form.min_length, '0');
  return out;
}

}  // namespace top
