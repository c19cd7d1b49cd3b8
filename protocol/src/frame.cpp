// Frames: the model's accessors, the checksum, and reusing and exchanging
// frames. The parser is in frame_parse.cpp and frame_checksum.cpp, the
// builder in frame_build.cpp.
#include "top/frame.hpp"

#include <cstdint>

#include "byte_sum.hpp"
#include "frame_parse.hpp"

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

}  // namespace top
