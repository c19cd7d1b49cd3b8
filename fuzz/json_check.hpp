// A strict, allocation-free JSON text validator for the capture targets'
// JSON Lines check. It accepts exactly what nlohmann::json::accept(text)
// accepts (RFC 8259: one value, surrounded by optional space, tab, CR or LF;
// strings of well-formed UTF-8 with no raw control characters, escapes
// \" \\ \/ \b \f \n \r \t \uXXXX with surrogates in pairs; numbers whose
// value is finite as a double; no depth limit), at a fraction of the cost:
// nlohmann's accept goes through its SAX parser and converts every number.
// tests/fuzz/fuzz_support_test.cpp checks the two agree on crafted and
// mutated texts, and the capture targets compare them on a sample of inputs.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

// The validator is the harness's check, not the code under test, and runs
// on every byte of every line a capture target writes. Its hot paths read
// through a raw pointer: in the fuzz build (clang, ASan + UBSan), UBSan's
// object-size checks made std::string_view's and std::array's accessors
// too big to inline, a call per byte (a tenth of a capture target's time),
// and for the same reason its own functions are built without UBSan (ASan
// stays). tests/fuzz/fuzz_support_test.cpp checks it against nlohmann,
// with UBSan in the asan preset (g++).
#ifdef __clang__
#pragma clang attribute push(__attribute__((no_sanitize("undefined"))), apply_to = function)
#endif

namespace topfuzz {

namespace json_detail {

// Nesting deeper than this is not judged (the validator recurses; the JSON
// the analyzer writes nests a few levels).
constexpr int kMaxDepth = 256;

struct Cursor {
  explicit Cursor(std::string_view text) : s(text), p(text.data()), n(text.size()) {}
  std::string_view s;
  const char* p;  // s's bytes and size, read without a call
  std::size_t n;
  std::size_t i = 0;
  int depth = 0;
  bool too_deep = false;
  int peek() const { return i < n ? static_cast<unsigned char>(p[i]) : -1; }
  void skip_space() {
    while (i < n && (p[i] == ' ' || p[i] == '\t' || p[i] == '\n' || p[i] == '\r')) ++i;
  }
  bool eat(std::string_view word) {
    if (n - i < word.size() || std::memcmp(p + i, word.data(), word.size()) != 0) return false;
    i += word.size();
    return true;
  }
};

inline int hex4(Cursor& c) {
  if (c.i + 4 > c.n) return -1;
  int v = 0;
  for (int k = 0; k < 4; ++k) {
    const char h = c.p[c.i++];
    int d;
    if (h >= '0' && h <= '9')
      d = h - '0';
    else if (h >= 'a' && h <= 'f')
      d = h - 'a' + 10;
    else if (h >= 'A' && h <= 'F')
      d = h - 'A' + 10;
    else
      return -1;
    v = v * 16 + d;
  }
  return v;
}

// One UTF-8 sequence starting with lead byte b (>= 0x80) at c.i - 1
// (RFC 3629 table: no overlongs, no surrogates, nothing above U+10FFFF).
inline bool utf8_tail(Cursor& c, unsigned b) {
  unsigned lo = 0x80, hi = 0xBF;
  int more;
  if (b >= 0xC2 && b <= 0xDF) {
    more = 1;
  } else if (b >= 0xE0 && b <= 0xEF) {
    more = 2;
    if (b == 0xE0) lo = 0xA0;
    if (b == 0xED) hi = 0x9F;
  } else if (b >= 0xF0 && b <= 0xF4) {
    more = 3;
    if (b == 0xF0) lo = 0x90;
    if (b == 0xF4) hi = 0x8F;
  } else {
    return false;
  }
  for (int k = 0; k < more; ++k) {
    const int x = c.peek();
    if (x < 0 || static_cast<unsigned>(x) < lo || static_cast<unsigned>(x) > hi) return false;
    ++c.i;
    lo = 0x80;
    hi = 0xBF;
  }
  return true;
}

// Bytes that stand for themselves inside a string: printable ASCII and DEL,
// but the quote and the backslash.
// (A plain array: std::array's operator[] is a function of the standard
// library, built with UBSan's checks.)
struct ByteTable {
  bool is[256];
};
inline constexpr ByteTable kPlain = [] {
  ByteTable t{};
  for (int b = 0x20; b < 0x80; ++b) t.is[b] = b != '"' && b != '\\';
  return t;
}();

inline bool string(Cursor& c) {
  ++c.i;  // opening quote
  const char* const p = c.p;
  const std::size_t n = c.n;
  while (true) {
    // a run of plain bytes at a time (most of a line), then one that is not
    std::size_t i = c.i;
    while (i < n && kPlain.is[static_cast<unsigned char>(p[i])]) ++i;
    c.i = i;
    const int x = c.peek();
    if (x < 0 || x < 0x20) return false;
    ++c.i;
    if (x == '"') return true;
    if (x == '\\') {
      const int e = c.peek();
      ++c.i;
      switch (e) {
        case '"':
        case '\\':
        case '/':
        case 'b':
        case 'f':
        case 'n':
        case 'r':
        case 't':
          break;
        case 'u': {
          const int u = hex4(c);
          if (u < 0) return false;
          if (u >= 0xDC00 && u <= 0xDFFF) return false;  // a lone low surrogate
          if (u >= 0xD800 && u <= 0xDBFF) {
            if (!c.eat("\\u")) return false;
            const int v = hex4(c);
            if (v < 0xDC00 || v > 0xDFFF) return false;
          }
          break;
        }
        default:
          return false;
      }
    } else if (x >= 0x80) {
      if (!utf8_tail(c, static_cast<unsigned>(x))) return false;
    }
  }
}

inline bool number(Cursor& c) {
  const std::size_t start = c.i;
  auto digit = [&] { return c.peek() >= '0' && c.peek() <= '9'; };
  if (c.peek() == '-') ++c.i;
  if (c.peek() == '0') {
    ++c.i;
  } else if (digit()) {
    while (digit()) ++c.i;
  } else {
    return false;
  }
  bool plain_int = true;
  if (c.peek() == '.') {
    plain_int = false;
    ++c.i;
    if (!digit()) return false;
    while (digit()) ++c.i;
  }
  if (c.peek() == 'e' || c.peek() == 'E') {
    plain_int = false;
    ++c.i;
    if (c.peek() == '+' || c.peek() == '-') ++c.i;
    if (!digit()) return false;
    while (digit()) ++c.i;
  }
  // nlohmann reads integers that do not fit 64 bits, and every number with
  // a fraction or exponent, as a double and rejects one that is not finite.
  if (plain_int && c.i - start <= 19) return true;
  // strtod needs a terminated copy: on the stack when it fits (the
  // analyzer's times and rates are short), else on the heap.
  const std::size_t len = c.i - start;
  char small[64];
  std::string big;
  const char* text = small;
  if (len < sizeof small) {
    std::memcpy(small, c.p + start, len);
    small[len] = '\0';
  } else {
    big.assign(c.p + start, len);
    text = big.c_str();
  }
  return std::isfinite(std::strtod(text, nullptr));
}

inline bool value(Cursor& c);

inline bool container(Cursor& c, char close, bool object) {
  if (++c.depth > kMaxDepth) {
    c.too_deep = true;
    return false;
  }
  ++c.i;
  c.skip_space();
  if (c.peek() == close) {
    ++c.i;
    --c.depth;
    return true;
  }
  while (true) {
    if (object) {
      if (c.peek() != '"' || !string(c)) return false;
      c.skip_space();
      if (c.peek() != ':') return false;
      ++c.i;
      c.skip_space();
    }
    if (!value(c)) return false;
    c.skip_space();
    if (c.peek() == close) {
      ++c.i;
      --c.depth;
      return true;
    }
    if (c.peek() != ',') return false;
    ++c.i;
    c.skip_space();
  }
}

inline bool value(Cursor& c) {
  switch (c.peek()) {
    case '{':
      return container(c, '}', true);
    case '[':
      return container(c, ']', false);
    case '"':
      return string(c);
    case 't':
      return c.eat("true");
    case 'f':
      return c.eat("false");
    case 'n':
      return c.eat("null");
    default:
      return number(c);
  }
}

}  // namespace json_detail

enum class Json { valid, invalid, too_deep };

// Whether `text` is one JSON value (what nlohmann::json::accept accepts; as
// there, a leading UTF-8 byte order mark is skipped and a NUL byte after the
// value ends the text); too_deep when
// it nests more than 256 levels before the verdict (ask nlohmann then).
inline Json json_check(std::string_view text) {
  json_detail::Cursor c(text);
  if (c.peek() == 0xEF) {
    if (!c.eat("\xEF\xBB\xBF")) return Json::invalid;
  }
  c.skip_space();
  const bool ok = json_detail::value(c);
  if (c.too_deep) return Json::too_deep;
  if (!ok) return Json::invalid;
  c.skip_space();
  // nlohmann's lexer takes a NUL byte for the end of input (for C strings):
  // whatever follows one after the value is not read.
  return c.i == text.size() || text[c.i] == '\0' ? Json::valid : Json::invalid;
}

// A deterministic sample of inputs: true for about one input in 2^bits,
// chosen from the input's bytes (FNV-1a), so a replay checks what the run
// checked.
inline bool sampled(const std::uint8_t* data, std::size_t size, unsigned bits) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 0x100000001b3ull;
  h ^= h >> 29;
  return (h & ((std::uint64_t{1} << bits) - 1)) == 0;
}

}  // namespace topfuzz

#ifdef __clang__
#pragma clang attribute pop
#endif
