// The session's per-frame prefilter: whether a frame's identifier may
// matter to a diagnosis at all, one switch instead of the rules' string
// compares (docs/perf/decisions.md, "Diagnoses prefilter"). Not the
// library's contract: the rules themselves are top/diagnoses.hpp's.
#pragma once

#include <cstdint>

namespace top::detail {

// A frame's identifier (3 chars) as one integer: a switch or a table of
// identifiers compares one word (this prefilter; the stream switches'
// keys, protocol/src/device.cpp).
constexpr std::uint32_t ident_key(const char* id) noexcept {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(id[0])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(id[1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(id[2])) << 16;
}

// Whether a frame of `ident` (3 chars) can matter to one of the rules of
// top/diagnoses.hpp: the identity replies, TRC and the dated frames
// (diagnoses_test checks it covers the rules). The decode gives it through
// a DecodeCache (top/detail/decode_cache.hpp), with the frame's shape.
inline bool may_matter_to_diagnoses(const char* ident) noexcept {
  switch (ident_key(ident)) {
    case ident_key("PA2"):
    case ident_key("VSN"):
    case ident_key("VER"):
    case ident_key("MOD"):
    case ident_key("TRC"):
    case ident_key("TIM"):
    case ident_key("UTC"):
      return true;
    default:
      return false;
  }
}

}  // namespace top::detail
