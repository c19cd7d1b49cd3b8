// A reference parser for the TOP frame, written straight from the two
// documents and sharing no code with protocol/src. It is deliberately
// simple and strict: it accepts exactly the frames the documents define and
// nothing else (no lying lengths, no lowercase digits, no TMP quirk, no
// CR/LF), so that on its domain the fast parser must agree with it.
//
// SkyDroid 2.2 / Topotek 1 (frame structure):
//   header (3 char) | src dst (2 char, U/M/D/E/P/G) | length (1 char) |
//   control (1 char, r = query, w = set) | identifier (3 char) |
//   data (length chars) | checksum (2 char)
//   #TP: fixed-length command (length char, documented as 2)
//   #tp: variable-length command, length is one ASCII hex digit, max 0x0F
//   #tP: (Topotek) the length is one raw byte (hex, not ASCII), max 0xFF
//   #Tp: (Topotek) the control position also carries length: two raw bytes,
//        max 0xFFFF; there is no control char
//   checksum: sum of the bytes from the header to the byte before the
//   checksum, as two ASCII hex digits, high digit first (appendix II; every
//   example writes them in uppercase).
// Identifiers: every identifier in both appendices is three uppercase
// letters or digits.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace topref {

// Views into the parsed bytes: valid as long as they are.
struct Frame {
  std::string_view header;  // "TP", "tp", "tP" or "Tp"
  char src = 0, dst = 0;
  char control = 0;  // 0 for #Tp
  std::string_view ident;
  std::size_t length = 0;  // declared data length
  std::size_t data_offset = 0;
  std::string_view data;
  unsigned checksum = 0;
  std::size_t size = 0;  // bytes of the whole frame
};

inline bool is_addr(char c) {
  return c == 'U' || c == 'M' || c == 'D' || c == 'E' || c == 'P' || c == 'G';
}

inline int upper_hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The frame the documents define at the start of `s`, if there is one.
inline std::optional<Frame> parse(std::string_view s) {
  Frame f;
  if (s.size() < 10 || s[0] != '#') return std::nullopt;
  f.header = s.substr(1, 2);
  if (f.header != "TP" && f.header != "tp" && f.header != "tP" && f.header != "Tp")
    return std::nullopt;
  f.src = s[3];
  f.dst = s[4];
  if (!is_addr(f.src) || !is_addr(f.dst)) return std::nullopt;
  if (f.header == "Tp") {
    f.length = static_cast<unsigned char>(s[5]) * 256u + static_cast<unsigned char>(s[6]);
  } else {
    if (f.header == "tP") {
      f.length = static_cast<unsigned char>(s[5]);
    } else {
      int v = upper_hex(s[5]);
      if (v < 0) return std::nullopt;
      f.length = static_cast<std::size_t>(v);
    }
    f.control = s[6];
    if (f.control != 'r' && f.control != 'w') return std::nullopt;
  }
  f.ident = s.substr(7, 3);
  for (char c : f.ident)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))) return std::nullopt;
  f.data_offset = 10;
  if (s.size() < 10 + f.length + 2) return std::nullopt;
  f.data = s.substr(10, f.length);
  unsigned sum = 0;
  for (std::size_t i = 0; i < 10 + f.length; ++i) sum += static_cast<unsigned char>(s[i]);
  int hi = upper_hex(s[10 + f.length]), lo = upper_hex(s[11 + f.length]);
  if (hi < 0 || lo < 0) return std::nullopt;
  f.checksum = static_cast<unsigned>(hi * 16 + lo);
  if (f.checksum != (sum & 0xFF)) return std::nullopt;
  f.size = 12 + f.length;
  return f;
}

// Field layouts the documents give for a few commands: hex fields of a
// width in chars, signed or not, and the placeholder the text allows in
// place of a value (Topotek ZFP: "if only zoom is set, fill focus with
// 'N''N''N''N'"). Only what the text says outright.
struct Field {
  int width;
  bool is_signed;
  const char* none = nullptr;
};

struct Layout {
  const char* dialect;  // "skydroid" or "topotek"
  const char* ident;
  char control;
  std::size_t length;
  std::vector<Field> fields;
};

inline const std::vector<Layout>& layouts() {
  // Built once (the field lists were built on every call, which the fuzz
  // targets make for each frame).
  using F = std::vector<Field>;
  static const F u2{{2, false}}, s2{{2, true}}, s2s2{{2, true}, {2, true}};
  static const F s2s2s2{{2, true}, {2, true}, {2, true}};
  static const F angle{{4, true}, {2, false}};
  static const F angle2{{4, true}, {2, false}, {4, true}, {2, false}};
  static const F att{{4, true}, {4, true}, {4, true}};
  static const F s4{{4, true}}, zoom_focus{{4, true}, {4, true, "NNNN"}};
  static const std::vector<Layout> all = {
      // SkyDroid 3.1 PTZ x1x2; 3.2 speed X0X1 "8-bit signed"; 3.3.1 angle
      // X0X1X2X3 "16-bit signed" + speed X4X5 hex; 3.3.2 GAA X0X1;
      // 3.3.2.2 GAC Y0Y1Y2Y3 P0P1P2P3 R0R1R2R3.
      {"skydroid", "PTZ", 'w', 2, u2},
      {"skydroid", "GSY", 'w', 2, s2},
      {"skydroid", "GSP", 'w', 2, s2},
      {"skydroid", "GSR", 'w', 2, s2},
      {"skydroid", "GSM", 'w', 4, s2s2},
      {"skydroid", "GAY", 'w', 6, angle},
      {"skydroid", "GAP", 'w', 6, angle},
      {"skydroid", "GAR", 'w', 6, angle},
      {"skydroid", "GAM", 'w', 12, angle2},
      {"skydroid", "GAA", 'w', 2, u2},
      {"skydroid", "GAC", 'r', 12, att},
      // Topotek 4.1 PTZ; 4.2 speed (GSM, RPS, YPR pairs of 8-bit signed);
      // 4.3 angle GAY/GAP/GAR/GAM and GIY/GIP/GIR/GIM; GAC reply; 3.x ZOM
      // and FOC replies (signed 16-bit, "FFB4 -> -76"); ZFP two of them.
      {"topotek", "PTZ", 'w', 2, u2},
      {"topotek", "GSY", 'w', 2, s2},
      {"topotek", "GSP", 'w', 2, s2},
      {"topotek", "GSR", 'w', 2, s2},
      {"topotek", "GSM", 'w', 4, s2s2},
      {"topotek", "RPS", 'w', 4, s2s2},
      {"topotek", "YPR", 'w', 6, s2s2s2},
      {"topotek", "GAY", 'w', 6, angle},
      {"topotek", "GAP", 'w', 6, angle},
      {"topotek", "GAR", 'w', 6, angle},
      {"topotek", "GAM", 'w', 12, angle2},
      {"topotek", "GIY", 'w', 6, angle},
      {"topotek", "GIP", 'w', 6, angle},
      {"topotek", "GIR", 'w', 6, angle},
      {"topotek", "GIM", 'w', 12, angle2},
      {"topotek", "GAC", 'r', 12, att},
      {"topotek", "ZOM", 'r', 4, s4},
      {"topotek", "FOC", 'r', 4, s4},
      {"topotek", "ZFP", 'w', 8, zoom_focus},
  };
  return all;
}

inline const Layout* find_layout(std::string_view dialect, const Frame& f) {
  for (const Layout& l : layouts())
    if (dialect == l.dialect && f.ident == l.ident && (f.control == 0 || f.control == l.control) &&
        f.length == l.length)
      return &l;
  return nullptr;
}

// A decoded hex field: valid when every char is a hex digit (either case)
// or it is the documented placeholder (none).
struct Value {
  bool valid = false;
  bool none = false;
  std::int64_t value = 0;
};

inline std::vector<Value> decode(const Layout& l, std::string_view data) {
  std::vector<Value> out;
  std::size_t at = 0;
  for (const Field& field : l.fields) {
    const int width = field.width;
    const bool is_signed = field.is_signed;
    Value v;
    v.valid = true;
    if (field.none != nullptr && data.substr(at, static_cast<std::size_t>(width)) == field.none) {
      v.none = true;
      out.push_back(v);
      at += static_cast<std::size_t>(width);
      continue;
    }
    std::uint64_t u = 0;
    for (int i = 0; i < width; ++i) {
      char c = data[at + static_cast<std::size_t>(i)];
      int d = upper_hex(c);
      if (d < 0 && c >= 'a' && c <= 'f') d = c - 'a' + 10;
      if (d < 0) v.valid = false;
      u = u * 16 + static_cast<unsigned>(d < 0 ? 0 : d);
    }
    const unsigned bits = static_cast<unsigned>(width) * 4;
    v.value = static_cast<std::int64_t>(u);
    if (is_signed && (u >> (bits - 1)) != 0) v.value -= static_cast<std::int64_t>(1) << bits;
    out.push_back(v);
    at += static_cast<std::size_t>(width);
  }
  return out;
}

}  // namespace topref
