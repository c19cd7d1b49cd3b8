// The repair pass of frame mutators: rewrites the length field and checksum
// of every frame in a buffer, so a mutated frame gets past the checksum and
// reaches the decoder. The fuzz targets' mutator and topconf fuzz share it.
// Inline: it runs on every mutation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "top/frame.hpp"

namespace top::detail {

// Rewrites, in place, the length field and checksum of each frame that
// starts at a '#' followed by TP, tp, tP or Tp. A frame's extent is taken to
// run from its header to the next '#', CR, LF or the end of the buffer; the
// last two bytes of that extent become the checksum of the bytes before them,
// and the length field is set to the data length in between (capped at the
// header's maximum, in which case the checksum goes where the cap says and
// the bytes after it are left as they are). Returns the number of frames
// repaired. Never changes the size.
inline std::size_t repair_frames(std::uint8_t* d, std::size_t size) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::size_t repaired = 0;
  std::size_t p = 0;
  while (p + 3 <= size) {
    if (d[p] != '#') {  // to the next '#' (memchr: this runs on every mutation)
      const void* h = std::memchr(d + p, '#', size - 2 - p);
      if (h == nullptr) break;
      p = static_cast<std::size_t>(static_cast<const std::uint8_t*>(h) - d);
    }
    const std::uint8_t h1 = d[p + 1], h2 = d[p + 2];
    const bool fixed = h1 == 'T' && h2 == 'P', variable = h1 == 't' && h2 == 'p';
    const bool ext8 = h1 == 't' && h2 == 'P', ext16 = h1 == 'T' && h2 == 'p';
    if (!(fixed || variable || ext8 || ext16)) {
      ++p;
      continue;
    }
    const std::size_t data_at = p + 10;
    // The extent ends at the first '#', CR or LF (memchr: this runs on
    // every mutation).
    std::size_t q = size;
    for (const int stop : {'#', '\r', '\n'})
      if (data_at < q)
        if (const void* h = std::memchr(d + data_at, stop, q - data_at))
          q = static_cast<std::size_t>(static_cast<const std::uint8_t*>(h) - d);
    if (q < data_at + 2) {  // no room for a checksum
      ++p;
      continue;
    }
    std::size_t len = q - 2 - data_at;
    const std::size_t cap = ext16 ? 0xFFFF : ext8 ? 0xFF : 0x0F;
    if (len > cap) len = cap;
    if (ext16) {
      d[p + 5] = static_cast<std::uint8_t>(len >> 8);
      d[p + 6] = static_cast<std::uint8_t>(len & 0xFF);
    } else if (ext8) {
      d[p + 5] = static_cast<std::uint8_t>(len);
    } else {
      d[p + 5] = static_cast<std::uint8_t>(kHex[len]);
    }
    const std::size_t cs = data_at + len;
    const unsigned sum =
        top::checksum(std::string_view(reinterpret_cast<const char*>(d + p), cs - p));
    d[cs] = static_cast<std::uint8_t>(kHex[(sum >> 4) & 0x0F]);
    d[cs + 1] = static_cast<std::uint8_t>(kHex[sum & 0x0F]);
    ++repaired;
    p = cs + 2;
  }
  return repaired;
}

}  // namespace top::detail
