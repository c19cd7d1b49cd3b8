// Firmware faults of topsim: what real firmware does on some inputs (stops
// answering until power-cycled, hangs for seconds, answers slowly, answers
// a frame it should have dropped). `topconf fuzz` is tested against them.
#include <algorithm>
#include <charconv>
#include <cstdio>

#include "sim/faults.hpp"
#include "top/catalog.hpp"

namespace topsim {

bool InputClass::matches(const top::Frame& f) const noexcept {
  switch (kind) {
    case Kind::none:
      return false;
    case Kind::ident:
      return f.ident_view() == ident;
    case Kind::length:
      return f.data_length == length;
    case Kind::byte:
      return f.raw.find(static_cast<char>(byte)) != std::string::npos;
  }
  return false;
}

std::string InputClass::to_string() const {
  switch (kind) {
    case Kind::none:
      return "";
    case Kind::ident:
      return "ident:" + ident;
    case Kind::length:
      return "len:" + std::to_string(length);
    case Kind::byte: {
      char b[8];
      std::snprintf(b, sizeof b, "byte:%02X", static_cast<unsigned>(byte));
      return b;
    }
  }
  return "";
}

std::optional<InputClass> parse_input_class(std::string_view s) {
  InputClass c;
  auto number = [](std::string_view v, int base, std::uint32_t max, std::uint32_t& out) {
    auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), out, base);
    return !v.empty() && ec == std::errc{} && p == v.data() + v.size() && out <= max;
  };
  if (s.size() == 3 && top::ident_index(s) >= 0) {
    c.kind = InputClass::Kind::ident;
    c.ident = std::string(s);
    return c;
  }
  const auto colon = s.find(':');
  if (colon == std::string_view::npos) return std::nullopt;
  const std::string_view k = s.substr(0, colon), v = s.substr(colon + 1);
  if (k == "ident" && v.size() == 3) {
    c.kind = InputClass::Kind::ident;
    c.ident = std::string(v);
    return c;
  }
  std::uint32_t n = 0;
  if (k == "len" && number(v, 10, top::max_data_ext16, n)) {
    c.kind = InputClass::Kind::length;
    c.length = n;
    return c;
  }
  if (k == "byte" && v.size() == 2 && number(v, 16, 0xFF, n)) {
    c.kind = InputClass::Kind::byte;
    c.byte = static_cast<std::uint8_t>(n);
    return c;
  }
  return std::nullopt;
}

bool FaultInjector::admit(top::Frame& request, std::uint64_t now_us) {
  now_us_ = now_us;
  if (crashed_ || now_us < hang_until_) return false;
  if (cfg_.crash_on.matches(request)) {
    crashed_ = true;
    return false;
  }
  if (cfg_.hang_class.matches(request)) {
    if (cfg_.hang_s == 0)
      hung_ = true;
    else
      hang_until_ = now_us + std::uint64_t{cfg_.hang_s} * 1000000;
    return false;
  }
  if (!on_request(request)) return false;
  if (cfg_.slow_on.matches(request))
    slow_until_ = std::max(slow_until_, now_us + std::uint64_t{cfg_.slow_ms} * 1000);
  if (cfg_.answer_corrupt && request.checksum_present && !request.checksum_ok &&
      request.raw.size() >= 2) {
    // The firmware skips the check: the frame as if its checksum were right.
    auto p = top::parse_exact(
        top::with_checksum(std::string_view(request.raw).substr(0, request.raw.size() - 2)));
    if (p.status == top::ParseStatus::frame) request = std::move(p.frame);
  }
  return true;
}

void FaultInjector::restart() noexcept {
  crashed_ = false;
  hung_ = false;
  hang_until_ = 0;
  slow_until_ = 0;
}

}  // namespace topsim
