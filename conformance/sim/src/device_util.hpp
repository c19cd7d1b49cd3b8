// Helpers the device's sources share (private to sim/).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "sim/device.hpp"
#include "top/top.hpp"

namespace topsim::detail {

// What a request handler of either dialect's table is given: the device,
// the request as framed and decoded, the time, and where its frames go.
struct HandlerCall {
  Device& dev;
  const top::Frame& req;
  const top::Decoded& dec;
  std::uint64_t now_us;
  std::vector<std::string>& out;
};
using HandlerFn = bool (*)(const HandlerCall&);

// An angle in degrees as signed 16-bit hex in 0.01 deg.
inline std::string hex_s16(double deg) {
  long v = std::lround(deg * 100.0);
  v = std::clamp(v, -32768L, 32767L);
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04X",
                static_cast<unsigned>(static_cast<std::uint16_t>(static_cast<std::int16_t>(v))));
  return buf;
}

inline std::string hex_u(std::uint64_t v, int width) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%0*llX", width, static_cast<unsigned long long>(v));
  return buf;
}

// A valid, present field of a decoded request, or null.
inline const top::FieldValue* field(const top::Decoded& d, std::string_view name) {
  for (const auto& f : d.fields)
    if (f.name() == name && f.valid && !f.none) return &f;
  return nullptr;
}

// Two hex digits of data as a number, -1 when they are not.
inline int data_byte(std::string_view data) noexcept {
  if (data.size() != 2) return -1;
  int hi = top::hex_value(data[0]), lo = top::hex_value(data[1]);
  if (hi < 0 || lo < 0) return -1;
  return hi * 16 + lo;
}

}  // namespace topsim::detail
