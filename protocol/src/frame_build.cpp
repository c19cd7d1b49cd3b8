// The frame builder: a BuildSpec's header, length encoding, identifier,
// data and checksum, with the deliberate malformations it asks for.
#include <cstdint>
#include <string>
#include <string_view>

#include "top/frame.hpp"

namespace top {

std::string build_frame(const BuildSpec& spec) {
  std::string out;
  build_frame(spec, out);
  return out;
}

void build_frame(const BuildSpec& spec, std::string& out) {
  Header h = spec.header;
  const std::size_t len = spec.data.size();
  if ((h == Header::fixed || h == Header::variable) && len > max_data_hex &&
      !spec.two_digit_length && !spec.keep_header)
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
  if (spec.omit_checksum) return;
  std::uint8_t sum = checksum(out);
  if (spec.checksum_header && *spec.checksum_header != h) {
    // The same bytes but the header's: the sum differs by the header chars.
    const std::string_view as = to_string(*spec.checksum_header), is = to_string(h);
    sum = static_cast<std::uint8_t>(sum - checksum(is) + checksum(as));
  }
  if (spec.checksum) sum = *spec.checksum;
  char cs[2];
  put_hex2(sum, cs);
  if (spec.lowercase_checksum)
    for (char& c : cs)
      if (c >= 'A' && c <= 'F') c = static_cast<char>(c - 'A' + 'a');
  out.append(cs, 2);
}

}  // namespace top
