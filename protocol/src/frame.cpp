#include "top/frame.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "chars.hpp"

namespace top {

using detail::cat;
using detail::hex_value;
using detail::is_hex;
using detail::is_lower_hex;

std::string_view Frame::checksum_text() const noexcept {
  if (!checksum_present) return {};
  std::size_t at = data_offset + data_length;
  return std::string_view(raw).substr(at, 2);
}

bool Frame::ok() const noexcept { return worst() != Severity::error; }

Severity Frame::worst() const noexcept {
  Severity w = Severity::info;
  for (const Finding& f : findings)
    if (f.severity > w) w = f.severity;
  return w;
}

bool Frame::has(FindingCode c) const noexcept {
  for (const Finding& f : findings)
    if (f.code == c) return true;
  return false;
}

namespace {

// The sum of n bytes, eight at a time (every frame is summed once or more).
unsigned byte_sum(const char* p, std::size_t n) noexcept {
  constexpr std::uint64_t kLow = 0x00FF00FF00FF00FFull;
  unsigned s = 0;
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t x;
    std::memcpy(&x, p + i, 8);
    // four 16-bit lanes of byte pairs, then their total in the top lane
    const std::uint64_t pairs = (x & kLow) + ((x >> 8) & kLow);
    s += static_cast<unsigned>((pairs * 0x0001000100010001ull) >> 48);
  }
  for (; i < n; ++i) s += static_cast<unsigned char>(p[i]);
  return s;
}

// byte_sum for n >= 8 without a loop over the last n % 8 bytes: the
// eight bytes that end at p + n make the last word, less the low bytes that
// the words before it summed already.
unsigned byte_sum8(const char* p, std::size_t n) noexcept {
  constexpr std::uint64_t kLow = 0x00FF00FF00FF00FFull;
  auto sum = [](std::uint64_t x) {
    const std::uint64_t pairs = (x & kLow) + ((x >> 8) & kLow);
    return static_cast<unsigned>((pairs * 0x0001000100010001ull) >> 48);
  };
  unsigned s = 0;
  std::size_t i = 0;
  std::uint64_t x;
  for (; i + 8 < n; i += 8) {
    std::memcpy(&x, p + i, 8);
    s += sum(x);
  }
  std::memcpy(&x, p + n - 8, 8);
  const std::size_t seen = i + 8 - n;  // 0-7 low bytes counted above
  if (std::endian::native == std::endian::little)
    x &= ~std::uint64_t{0} << (8 * seen);
  else
    x &= ~std::uint64_t{0} >> (8 * seen);
  return s + sum(x);
}

// dst[0, n) = src[0, n) for 8 <= n <= 32 in four eight-byte moves, the last
// ones overlapping (no length-dependent branch, no string instruction).
void copy_short(char* dst, const char* src, std::size_t n) noexcept {
  for (std::size_t j = 0; j < 32; j += 8) {
    const std::size_t at = std::min(j, n - 8);
    std::uint64_t x;
    std::memcpy(&x, src + at, 8);
    std::memcpy(dst + at, &x, 8);
  }
}

}  // namespace

std::uint8_t checksum(std::string_view bytes) noexcept {
  const unsigned s = bytes.size() >= 8 ? byte_sum8(bytes.data(), bytes.size())
                                       : byte_sum(bytes.data(), bytes.size());
  return static_cast<std::uint8_t>(s & 0xFF);
}

void put_hex2(std::uint8_t v, char out[2]) noexcept {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  out[0] = kDigits[v >> 4];
  out[1] = kDigits[v & 0x0F];
}

void reset_keep_capacity(Frame& f) noexcept {
  f.header = Header::variable;
  f.src = f.dst = f.control = 0;
  f.ident[0] = f.ident[1] = f.ident[2] = 0;
  f.declared_length = f.data_offset = f.data_length = 0;
  f.checksum = f.expected_checksum = 0;
  f.checksum_present = f.checksum_ok = false;
  f.terminator = 0;
  f.raw.clear();
  f.findings.clear();
}

void swap(Frame& a, Frame& b) noexcept {
  using std::swap;
  swap(a.header, b.header);
  swap(a.src, b.src);
  swap(a.dst, b.dst);
  swap(a.control, b.control);
  swap(a.ident, b.ident);
  swap(a.declared_length, b.declared_length);
  swap(a.data_offset, b.data_offset);
  swap(a.data_length, b.data_length);
  swap(a.checksum, b.checksum);
  swap(a.expected_checksum, b.expected_checksum);
  swap(a.checksum_present, b.checksum_present);
  swap(a.checksum_ok, b.checksum_ok);
  swap(a.terminator, b.terminator);
  a.raw.swap(b.raw);
  a.findings.swap(b.findings);
}

std::string with_checksum(std::string_view s) {
  std::string out(s);
  char c[2];
  put_hex2(checksum(s), c);
  out.append(c, 2);
  return out;
}

namespace {

std::string hex2(std::uint8_t v) {
  char b[2];
  put_hex2(v, b);
  return std::string(b, 2);
}

std::string printable(char c) {
  auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7F) return {'\'', c, '\''};
  char b[8];
  std::snprintf(b, sizeof b, "0x%02X", u);
  return b;
}

bool is_boundary(char c) noexcept { return c == '#' || c == '\r' || c == '\n'; }

// A parse's verdict without its frame (built in place by parse_into) or its
// error (written to the caller's Finding only when invalid).
struct Verdict {
  ParseStatus status = ParseStatus::need_more;
  std::size_t consumed = 0;
};

Verdict invalid(Finding& err, FindingCode code, std::size_t offset, std::string msg) {
  // In place, as make_finding would build it: the stream decoder parses at
  // every '#', most of them fail, and a Finding built and moved in costs more
  // than the parse.
  err.code = code;
  err.severity = default_severity(code);
  err.offset = static_cast<std::uint32_t>(offset);
  err.message = std::move(msg);
  err.quirk = {};
  return Verdict{ParseStatus::invalid, 0};
}

// `until`: the input length below which the verdict stays need_more (0
// when the parse cannot tell).
Verdict need_more(std::size_t until = 0) { return Verdict{ParseStatus::need_more, until}; }

Verdict truncated(Finding& err, std::size_t have, std::size_t want) {
  return invalid(err, FindingCode::truncated, have,
                 cat({"input ends after ", std::to_string(have), " bytes of a frame that needs ",
                      std::to_string(want)}));
}

// Header variants whose checksum a sender may have used by mistake.
constexpr std::array<std::array<char, 2>, 4> kHeaderVariants = {
    {{'T', 'P'}, {'t', 'p'}, {'t', 'P'}, {'T', 'p'}}};

// State shared by the steps of one parse.
struct Layout {
  Header header = Header::variable;
  char control = 0;
  std::size_t ident_at = 7;
  std::size_t data_at = prefix_size;
  std::size_t declared = 0;
  bool hex_length = true;  // length is hex digits (alternatives make sense)
  bool two_digit = false;
};

// Checks the checksum digits at `p`; fills frame fields. Returns true when
// the two digits are hex and equal to the sum of bytes [0, p).
bool checksum_at(std::string_view b, std::size_t p, unsigned prefix_sum,
                 std::uint8_t& value) noexcept {
  if (p + 2 > b.size()) return false;
  int hi = hex_value(b[p]), lo = hex_value(b[p + 1]);
  if (hi < 0 || lo < 0) return false;
  value = static_cast<std::uint8_t>(hi * 16 + lo);
  return value == static_cast<std::uint8_t>(prefix_sum & 0xFF);
}

// The common frame in one pass: #TP or #tp, two addresses, an uppercase hex
// length char, r or w, an identifier, the declared data and two uppercase
// checksum digits that match. These are exactly the frames on which the
// general parse below gives no finding and keeps the declared length, and it
// builds the same frame; false (with `f` untouched) sends every other input
// there.
bool parse_plain(std::string_view b, const ParseOptions& opts, Frame& f, Verdict& r) {
  const std::size_t n = b.size();
  if (n < prefix_size + 2 || b[0] != '#') return false;
  const bool fixed = b[1] == 'T' && b[2] == 'P';
  if (!fixed && !(b[1] == 't' && b[2] == 'p')) return false;
  const int len = hex_value(b[5]);
  if (!is_address(b[3]) || !is_address(b[4]) || len < 0 || is_lower_hex(b[5]) ||
      (b[6] != 'r' && b[6] != 'w') || !is_ident_char(b[7]) || !is_ident_char(b[8]) ||
      !is_ident_char(b[9]))
    return false;
  const auto L = static_cast<std::size_t>(len);
  const std::size_t cs = prefix_size + L;
  if (L > opts.max_data_length || n < cs + 2 || is_lower_hex(b[cs]) || is_lower_hex(b[cs + 1]))
    return false;
  const unsigned prefix = byte_sum8(b.data(), cs);  // cs >= prefix_size
  std::uint8_t value = 0;
  if (!checksum_at(b, cs, prefix, value)) return false;
  f.header = fixed ? Header::fixed : Header::variable;
  f.src = b[3];
  f.dst = b[4];
  f.control = b[6];
  f.ident[0] = b[7];
  f.ident[1] = b[8];
  f.ident[2] = b[9];
  f.declared_length = static_cast<std::uint32_t>(L);
  f.data_offset = static_cast<std::uint32_t>(prefix_size);
  f.data_length = static_cast<std::uint32_t>(L);
  f.checksum = f.expected_checksum = value;
  f.checksum_present = f.checksum_ok = true;
  f.terminator = 0;
  f.raw.resize(cs + 2);  // fills only past the last frame's length
  copy_short(f.raw.data(), b.data(), cs + 2);
  f.findings.clear();
  r = Verdict{ParseStatus::frame, cs + 2};
  return true;
}

// The general parser (parse_frame tries parse_plain first). A frame is
// built in `f` (reset first), which the result refers to only when its
// status is frame.
Verdict parse_into(std::string_view b, bool at_end, const ParseOptions& opts, Frame& f,
                   Finding& err) {
  reset_keep_capacity(f);
  // A finding's text, built only when the caller keeps it.
  auto text = [&](auto&& build) { return opts.messages ? std::string(build()) : std::string(); };
  auto cut = [&](std::size_t have, std::size_t want) {
    return opts.messages ? truncated(err, have, want)
                         : invalid(err, FindingCode::truncated, have, {});
  };
  const std::size_t n = b.size();
  auto short_of = [&](std::size_t want) { return n < want; };
  if (n == 0) return at_end ? cut(0, 1) : need_more();
  if (b[0] != '#')
    return invalid(err, FindingCode::bad_header, 0, text([&] {
                     return cat({"frame must start with '#', got ", printable(b[0])});
                   }));

  Layout lay;
  // --- header -----------------------------------------------------------
  if (short_of(2)) return at_end ? cut(n, 12) : need_more();
  if (b[1] == 'P') {
    // Topotek 12.2 documents "#PDP16TMP<22 chars><RR>": no 'tp', no control.
    static constexpr std::string_view kTmp = "#PDP??TMP";
    for (std::size_t i = 1; i < kTmp.size(); ++i) {
      if (i >= n) return at_end ? cut(n, 33) : need_more();
      bool okc = kTmp[i] == '?' ? is_hex(b[i]) : b[i] == kTmp[i];
      if (!okc)
        return invalid(err, FindingCode::bad_header, 1, text([&] {
                         return cat({"'#' followed by ", printable(b[1]),
                                     ", not a TOP header (#TP #tp #tP #Tp)"});
                       }));
    }
    lay.header = Header::tmp_quirk;
    lay.ident_at = 6;
    lay.data_at = 9;
    lay.declared =
        static_cast<std::size_t>(hex_value(b[4])) * 16 + static_cast<std::size_t>(hex_value(b[5]));
    lay.hex_length = false;
  } else {
    if (b[1] != 'T' && b[1] != 't')
      return invalid(err, FindingCode::bad_header, 1, text([&] {
                       return cat({"'#' followed by ", printable(b[1]),
                                   ", not a TOP header (#TP #tp #tP #Tp)"});
                     }));
    if (short_of(3)) return at_end ? cut(n, 12) : need_more();
    if (b[2] != 'P' && b[2] != 'p')
      return invalid(err, FindingCode::bad_header, 2, text([&] {
                       return cat({"\"#", b.substr(1, 1), "\" followed by ", printable(b[2]),
                                   ", not a TOP header"});
                     }));
    if (b[1] == 'T')
      lay.header = b[2] == 'P' ? Header::fixed : Header::ext16;
    else
      lay.header = b[2] == 'p' ? Header::variable : Header::ext8;
  }

  f.header = lay.header;
  std::vector<Finding>& notes = f.findings;

  if (lay.header != Header::tmp_quirk) {
    // --- addresses --------------------------------------------------------
    for (std::size_t i = 3; i < 5; ++i) {
      if (short_of(i + 1)) return at_end ? cut(n, 12) : need_more();
      if (!is_address(b[i]))
        return invalid(err, FindingCode::bad_address, i, text([&] {
                         return cat({i == 3 ? "source" : "destination", " address ",
                                     printable(b[i]), " is not one of U M D E P G"});
                       }));
    }
    // --- length and control ----------------------------------------------
    if (short_of(6)) return at_end ? cut(n, 12) : need_more();
    switch (lay.header) {
      case Header::fixed:
      case Header::variable: {
        if (!is_hex(b[5]))
          return invalid(err, FindingCode::bad_length_char, 5, text([&] {
                           return cat({"length char ", printable(b[5]), " is not a hex digit"});
                         }));
        if (is_lower_hex(b[5]))
          notes.push_back(make_finding(FindingCode::lowercase_hex, 5,
                                       text([] { return "length char written in lowercase"; })));
        if (short_of(7)) return at_end ? cut(n, 12) : need_more();
        if (b[6] == 'r' || b[6] == 'w') {
          lay.control = b[6];
          lay.declared = static_cast<std::size_t>(hex_value(b[5]));
        } else if (is_hex(b[6])) {
          // Two-digit length ("#tpDP16wTMP..."): the TMP firmware quirk.
          if (short_of(8)) return at_end ? cut(n, 13) : need_more();
          if (b[7] != 'r' && b[7] != 'w')
            return invalid(err, FindingCode::bad_control, 6, text([&] {
                             return cat({"control char ", printable(b[6]), " is not r or w"});
                           }));
          lay.control = b[7];
          lay.declared = static_cast<std::size_t>(hex_value(b[5])) * 16 +
                         static_cast<std::size_t>(hex_value(b[6]));
          lay.two_digit = true;
          lay.hex_length = false;
          lay.ident_at = 8;
          lay.data_at = 11;
        } else {
          return invalid(err, FindingCode::bad_control, 6, text([&] {
                           return cat({"control char ", printable(b[6]), " is not r or w"});
                         }));
        }
        break;
      }
      case Header::ext8: {
        lay.declared = static_cast<unsigned char>(b[5]);
        lay.hex_length = false;
        if (short_of(7)) return at_end ? cut(n, 12) : need_more();
        if (b[6] != 'r' && b[6] != 'w')
          return invalid(err, FindingCode::bad_control, 6, text([&] {
                           return cat({"control char ", printable(b[6]), " is not r or w"});
                         }));
        lay.control = b[6];
        break;
      }
      case Header::ext16: {
        if (short_of(7)) return at_end ? cut(n, 12) : need_more();
        lay.declared = static_cast<std::size_t>(static_cast<unsigned char>(b[5]) << 8 |
                                                static_cast<unsigned char>(b[6]));
        lay.hex_length = false;
        lay.control = 0;
        lay.ident_at = 7;
        lay.data_at = 10;
        break;
      }
      case Header::tmp_quirk:
        break;
    }
  }

  // --- identifier -----------------------------------------------------------
  for (std::size_t i = lay.ident_at; i < lay.ident_at + 3; ++i) {
    if (short_of(i + 1)) return at_end ? cut(n, lay.data_at + 2) : need_more();
    if (!is_ident_char(b[i]))
      return invalid(err, FindingCode::bad_ident, i, text([&] {
                       return cat({"identifier char ", printable(b[i]),
                                   " is not an uppercase letter or digit"});
                     }));
  }
  if (lay.declared > opts.max_data_length)
    return invalid(err, FindingCode::frame_too_long, 5, text([&] {
                     return cat({"declared data length ", std::to_string(lay.declared),
                                 " exceeds the limit of ", std::to_string(opts.max_data_length)});
                   }));

  f.src = lay.header == Header::tmp_quirk ? b[2] : b[3];
  f.dst = lay.header == Header::tmp_quirk ? b[3] : b[4];
  f.control = lay.control;
  f.ident[0] = b[lay.ident_at];
  f.ident[1] = b[lay.ident_at + 1];
  f.ident[2] = b[lay.ident_at + 2];
  f.declared_length = static_cast<std::uint32_t>(lay.declared);
  f.data_offset = static_cast<std::uint32_t>(lay.data_at);

  if (lay.header == Header::tmp_quirk || (lay.two_digit && f.ident_view() == "TMP")) {
    notes.push_back(
        make_finding(FindingCode::tmp_quirk, lay.header == Header::tmp_quirk ? 1 : 5, text([&] {
                       return lay.header == Header::tmp_quirk
                                  ? "the malformed TMP form documented in Topotek 12.2 "
                                    "(#PDP16TMP: no 'tp', two-digit length, no control char)"
                                  : "TMP frame with a two-digit length (Topotek 12.2: 22 data "
                                    "chars do not fit one hex digit)";
                     }),
                     "topotek-tmp-length"));
  } else if (lay.two_digit) {
    notes.push_back(
        make_finding(FindingCode::two_digit_length, 5, text([&] {
                       return cat({"length written as two hex digits (0x", b.substr(5, 2), ")"});
                     })));
  }

  // --- data and checksum -------------------------------------------------------
  const std::size_t L = lay.declared;
  const std::size_t declared_cs = lay.data_at + L;
  const std::size_t declared_end = declared_cs + 2;
  // Look-ahead needed to judge other data lengths: every one-digit length
  // plus its checksum and the byte after it.
  const std::size_t lookahead = lay.data_at + max_data_hex + 3;

  // Every byte before the data is read: nothing changes until the checksum.
  if (!at_end && n < declared_end) return need_more(declared_end);

  // Sum of bytes [0, p).
  auto sum_to = [&](std::size_t p) { return byte_sum(b.data(), p); };

  auto finish = [&](std::size_t data_len, bool present, std::uint8_t value,
                    unsigned prefix) -> Verdict {
    Verdict r{ParseStatus::frame, 0};
    f.data_length = static_cast<std::uint32_t>(data_len);
    std::size_t end = lay.data_at + data_len + (present ? 2 : 0);
    f.raw.append(b.data(), end);  // empty since the reset (cheaper than assign)
    f.expected_checksum = static_cast<std::uint8_t>(prefix & 0xFF);
    f.checksum_present = present;
    f.checksum = value;
    f.checksum_ok = present && value == f.expected_checksum;
    r.consumed = end;
    return r;
  };

  unsigned prefix_declared = 0;
  if (n >= declared_end) {
    prefix_declared = sum_to(declared_cs);
    std::uint8_t v = 0;
    if (checksum_at(b, declared_cs, prefix_declared, v)) {
      if (is_lower_hex(b[declared_cs]) || is_lower_hex(b[declared_cs + 1]))
        notes.push_back(make_finding(
            FindingCode::checksum_case, static_cast<std::uint32_t>(declared_cs), text([&] {
              return cat({"checksum ", b.substr(declared_cs, 2),
                          " is right but lowercase; strict receivers expect ", hex2(v)});
            })));
      return finish(L, true, v, prefix_declared);
    }
  }

  // The declared boundary does not validate.
  if (lay.hex_length && opts.recover_lying_length) {
    if (!at_end && n < lookahead) return need_more(lookahead);
    std::size_t found = SIZE_MAX;
    int count = 0;
    std::uint8_t found_value = 0;
    unsigned found_prefix = 0;
    unsigned s = sum_to(lay.data_at);
    for (std::size_t dl = 0; dl <= max_data_hex; ++dl) {
      std::size_t p = lay.data_at + dl;
      if (dl > 0) s += static_cast<unsigned char>(b[p - 1]);
      if (p + 2 > n) break;
      if (dl == L) continue;
      std::uint8_t v = 0;
      if (!checksum_at(b, p, s, v)) continue;
      bool bounded = (p + 2 == n && at_end) || (p + 2 < n && is_boundary(b[p + 2]));
      if (!bounded) continue;
      ++count;
      found = dl;
      found_value = v;
      found_prefix = s;
    }
    if (count == 1) {
      notes.push_back(
          make_finding(FindingCode::length_mismatch, 5, text([&] {
                         return cat({"declared length ", std::to_string(L),
                                     " but the checksum validates with ", std::to_string(found),
                                     " data bytes; decoded with ", std::to_string(found)});
                       })));
      return finish(found, true, found_value, found_prefix);
    }
  }

  if (n < declared_end) {
    // Only reachable at the end of input.
    if (n == declared_cs) {
      unsigned p = sum_to(declared_cs);
      notes.push_back(
          make_finding(FindingCode::no_checksum, static_cast<std::uint32_t>(declared_cs), text([&] {
                         return cat({"frame ends where its checksum should be (expected ",
                                     hex2(static_cast<std::uint8_t>(p)), ")"});
                       })));
      return finish(L, false, 0, p);
    }
    return cut(n, declared_end);
  }

  // No checksum at all: the data is followed directly by a boundary.
  if (is_boundary(b[declared_cs])) {
    notes.push_back(
        make_finding(FindingCode::no_checksum, static_cast<std::uint32_t>(declared_cs), text([&] {
                       return cat({"frame ends where its checksum should be (expected ",
                                   hex2(static_cast<std::uint8_t>(prefix_declared)), ")"});
                     })));
    return finish(L, false, 0, prefix_declared);
  }

  // A wrong checksum: say whether it is the sum under another header case.
  std::uint8_t expected = static_cast<std::uint8_t>(prefix_declared & 0xFF);
  const std::string_view got = b.substr(declared_cs, 2);
  int hi = hex_value(b[declared_cs]), lo = hex_value(b[declared_cs + 1]);
  bool present = hi >= 0 && lo >= 0;
  std::uint8_t value = present ? static_cast<std::uint8_t>(hi * 16 + lo) : 0;
  if (present && lay.header != Header::tmp_quirk) {
    unsigned base =
        prefix_declared - static_cast<unsigned char>(b[1]) - static_cast<unsigned char>(b[2]);
    for (const auto& v : kHeaderVariants) {
      if (v[0] == b[1] && v[1] == b[2]) continue;
      unsigned alt = base + static_cast<unsigned char>(v[0]) + static_cast<unsigned char>(v[1]);
      if (static_cast<std::uint8_t>(alt & 0xFF) == value) {
        notes.push_back(make_finding(FindingCode::checksum_header_case,
                                     static_cast<std::uint32_t>(declared_cs), text([&] {
                                       return cat({"checksum ",
                                                   got,
                                                   " is the sum with header #",
                                                   {v.data(), 2},
                                                   ", not #",
                                                   b.substr(1, 2),
                                                   " (expected ",
                                                   hex2(expected),
                                                   ")"});
                                     }),
                                     "skydroid-doc-header-case"));
        return finish(L, true, value, prefix_declared);
      }
    }
  }
  notes.push_back(make_finding(FindingCode::bad_checksum, static_cast<std::uint32_t>(declared_cs),
                               present ? text([&] {
                                 return cat({"checksum ", got, ", expected ", hex2(expected)});
                               })
                                       : text([&] {
                                           return cat({"checksum field '", got,
                                                       "' is not two hex digits, expected ",
                                                       hex2(expected)});
                                         })));
  return finish(L, present, value, prefix_declared);
}

}  // namespace

ParseResult parse_frame(std::string_view bytes, bool at_end, const ParseOptions& opts) {
  ParseResult r;
  parse_frame(bytes, at_end, opts, r);
  return r;
}

void parse_frame(std::string_view bytes, bool at_end, const ParseOptions& opts, ParseResult& out) {
  // the error of an earlier parse goes (most parses have none to write)
  if (out.error.code != FindingCode{} || !out.error.message.empty()) out.error = Finding{};
  // the common frame here, without parse_into's entry (it saves the
  // registers of the whole general parse)
  if (Verdict plain; opts.fast_path && parse_plain(bytes, opts, out.frame, plain)) {
    out.status = plain.status;
    out.consumed = plain.consumed;
    return;
  }
  const Verdict r = parse_into(bytes, at_end, opts, out.frame, out.error);
  out.status = r.status;
  out.consumed = r.consumed;
  if (r.status != ParseStatus::frame) reset_keep_capacity(out.frame);
}

void parse_exact(std::string_view bytes, const ParseOptions& opts, ParseResult& r) {
  parse_frame(bytes, true, opts, r);
  if (r.status != ParseStatus::frame) return;
  std::size_t i = r.consumed;
  std::size_t crlf = 0;
  while (i < bytes.size() && (bytes[i] == '\r' || bytes[i] == '\n')) {
    ++i;
    ++crlf;
  }
  if (crlf > 0) {
    r.frame.terminator = static_cast<std::uint8_t>(std::min(crlf, kMaxTerminator));
    r.frame.findings.push_back(
        make_finding(FindingCode::crlf, static_cast<std::uint32_t>(r.consumed),
                     cat({"frame followed by ", std::to_string(crlf), " CR/LF byte(s)"})));
  }
  if (i < bytes.size())
    r.frame.findings.push_back(
        make_finding(FindingCode::trailing_bytes, static_cast<std::uint32_t>(i),
                     cat({std::to_string(bytes.size() - i), " byte(s) after the frame"})));
  r.consumed = bytes.size();
}

ParseResult parse_exact(std::string_view bytes, const ParseOptions& opts) {
  ParseResult r;
  parse_exact(bytes, opts, r);
  return r;
}

std::string build_frame(const BuildSpec& spec) {
  std::string out;
  build_frame(spec, out);
  return out;
}

void build_frame(const BuildSpec& spec, std::string& out) {
  Header h = spec.header;
  const std::size_t len = spec.data.size();
  if ((h == Header::fixed || h == Header::variable) && len > max_data_hex && !spec.two_digit_length)
    h = Header::ext8;
  if (h == Header::ext8 && len > max_data_ext8) h = Header::ext16;
  if (h == Header::tmp_quirk) h = Header::variable;
  const std::size_t declared = spec.declared_length.value_or(static_cast<std::uint32_t>(len));
  static constexpr char kHex[] = "0123456789ABCDEF";
  out.clear();
  out.reserve(prefix_size + len + 3);
  out += to_string(h);
  out += spec.src;
  out += spec.dst;
  switch (h) {
    case Header::fixed:
    case Header::variable:
      if (spec.two_digit_length) out += kHex[(declared >> 4) & 0x0F];
      out += kHex[declared & 0x0F];
      out += spec.control;
      break;
    case Header::ext8:
      out += static_cast<char>(declared & 0xFF);
      out += spec.control;
      break;
    case Header::ext16:
      out += static_cast<char>((declared >> 8) & 0xFF);
      out += static_cast<char>(declared & 0xFF);
      break;
    case Header::tmp_quirk:
      break;
  }
  out.append(spec.ident.substr(0, 3));
  out.append(spec.data);
  std::uint8_t sum = checksum(out);
  if (spec.checksum_header && *spec.checksum_header != h) {
    // The same bytes but the header's: the sum differs by the header chars.
    const std::string_view as = to_string(*spec.checksum_header), is = to_string(h);
    sum = static_cast<std::uint8_t>(sum - checksum(is) + checksum(as));
  }
  char cs[2];
  put_hex2(sum, cs);
  if (spec.lowercase_checksum)
    for (char& c : cs)
      if (c >= 'A' && c <= 'F') c = static_cast<char>(c - 'A' + 'a');
  out.append(cs, 2);
}

}  // namespace top
