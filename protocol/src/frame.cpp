// Frames: the model's accessors, the checksum, and reusing and exchanging
// frames. The parser is in frame_parse.cpp and frame_checksum.cpp, the
// builder in frame_build.cpp.
#include "top/frame.hpp"

#include <cstdint>

#include "byte_sum.hpp"
#include "frame_parse.hpp"
#include "swap_members.hpp"

namespace top {

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

std::uint8_t checksum(std::string_view bytes) noexcept {
  const unsigned s = bytes.size() >= 8 ? detail::byte_sum8(bytes.data(), bytes.size())
                                       : detail::byte_sum(bytes.data(), bytes.size());
  return static_cast<std::uint8_t>(s & 0xFF);
}

void put_hex2(std::uint8_t v, char out[2]) noexcept {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  out[0] = kDigits[v >> 4];
  out[1] = kDigits[v & 0x0F];
}

void reset_keep_capacity(Frame& f) noexcept { detail::reset_frame(f); }

void swap(Frame& a, Frame& b) noexcept {
  detail::swap_members(a, b, &Frame::header, &Frame::src, &Frame::dst, &Frame::control,
                       &Frame::ident, &Frame::declared_length, &Frame::data_offset,
                       &Frame::data_length, &Frame::checksum, &Frame::expected_checksum,
                       &Frame::checksum_present, &Frame::checksum_ok, &Frame::terminator,
                       &Frame::raw, &Frame::findings);
}

std::string with_checksum(std::string_view s) {
  std::string out(s);
  char c[2];
  put_hex2(checksum(s), c);
  out.append(c, 2);
  return out;
}

}  // namespace top
