// Reading two field kinds from their bytes, for decode.cpp's decode_field:
// binary integers and NMEA-style coordinates.
#pragma once

#include <cmath>
#include <cstdint>
#include <string_view>

#include "numbers.hpp"
#include "top/catalog.hpp"

namespace top::detail {

// A little- or big-endian binary integer field of 2 or 4 bytes, or a byte
// (the size checked), signed or not as its kind says.
inline std::int64_t binary_int(FieldKind kind, std::string_view bytes) {
  if (kind == FieldKind::u8) return bytes.empty() ? 0 : static_cast<unsigned char>(bytes[0]);
  const bool big = kind == FieldKind::be_i16 || kind == FieldKind::be_u16;
  const std::size_t w = bytes.size();
  std::uint32_t u = 0;
  for (std::size_t i = 0; i < w; ++i)
    u |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i]))
         << (8 * (big ? w - 1 - i : i));
  if (kind == FieldKind::le_i16 || kind == FieldKind::be_i16)
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(u));
  if (kind == FieldKind::le_u16 || kind == FieldKind::be_u16) return static_cast<std::uint16_t>(u);
  return static_cast<std::int32_t>(u);
}

// A coordinate, "E" + dddmm.mmmm or "N" + ddmm.mmmm (as in $GPGGA), into
// signed degrees `v`; false after `bad` (the field's complaint) when it is
// no such coordinate.
template <class Bad>
inline bool decode_nmea(std::string_view bytes, double& v, Bad& bad) {
  if (bytes.size() < 2) {
    bad("too short for a hemisphere and a coordinate");
    return false;
  }
  const char hemi = bytes[0];
  if (hemi != 'E' && hemi != 'W' && hemi != 'N' && hemi != 'S') {
    bad("hemisphere '", {&hemi, 1}, "' is not N S E W");
    return false;
  }
  // Degrees in 3 digits east or west, 2 north or south, leading zeros
  // sent (Topotek 5.8.1, 5.8.2), then minutes mm.mmmm: the 5.8.7
  // output's ddd.ddddd (same length) is no such coordinate.
  const std::size_t deg_digits = hemi == 'E' || hemi == 'W' ? 3 : 2;
  const std::string_view coord = bytes.substr(1);
  bool shaped = coord.size() == deg_digits + 7 && coord[deg_digits + 2] == '.';
  for (std::size_t i = 0; shaped && i < coord.size(); ++i)
    shaped = i == deg_digits + 2 || (coord[i] >= '0' && coord[i] <= '9');
  double raw = 0;
  if (!shaped || !parse_number(coord, raw) || raw - std::floor(raw / 100.0) * 100.0 >= 60.0) {
    bad("'", coord, deg_digits == 3 ? "' is not dddmm.mmmm" : "' is not ddmm.mmmm");
    return false;
  }
  const double deg = std::floor(raw / 100.0);
  v = deg + (raw - deg * 100.0) / 60.0;
  if (hemi == 'W' || hemi == 'S') v = -v;
  return true;
}

}  // namespace top::detail
