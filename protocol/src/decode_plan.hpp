// Internal: the verdict without detail, planned per form.
//
// Most forms are a few hex fields of 1-8 chars, at most 16 chars in all.
// Without detail such a form is judged with few branches and none on its
// digits: the whole data is checked for 0-9 A-F as two eight-byte words,
// and only the fields that have a range or labels are converted (lane-wise,
// from one word each) and compared with integer bounds worked out once from
// the field's scaled range. Frames of every identifier arrive interleaved, so
// the per-char loops, scale tests and comparisons of decode_field mispredict
// often. Any byte outside 0-9 A-F sends the whole form back to check_field,
// which gives the exact findings.

#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "top/catalog.hpp"

namespace top::detail {

inline constexpr std::uint64_t kOnes = 0x0101010101010101ull, kTops = 0x8080808080808080ull;

// The top `n` (0-8; no more) bytes of a word as their top bits, and as
// whole bytes.
constexpr std::uint64_t top_lanes(unsigned n) noexcept { return n ? kTops << (8 * (8 - n)) : 0; }
constexpr std::uint64_t top_bytes(unsigned n) noexcept { return (top_lanes(n) >> 7) * 0xFF; }

// A field that has a range or labels.
struct FieldCheck {
  std::uint32_t end = 0;                        // offset in the data just past the field
  std::uint32_t bits = 0;                       // 4 per char
  std::uint64_t bytes = 0;                      // the field's chars in the word that ends with it
  std::uint64_t sign_bit = 0;                   // hex_s: the top bit of the value (0: unsigned)
  std::uint64_t label_bits = 0;                 // which values 0-63 have a label
  bool labels = false;                          // a value with a label is exempt from the range
  bool enum_only = false;                       // enum_hex: a value without a label is out of range
  std::int64_t lo = INT64_MIN, hi = INT64_MAX;  // the integers inside the range
};

struct FormPlan {
  bool fast = false;        // every field is planned and the form has no "none" data
  std::uint32_t width = 0;  // the data length the fields cover (at most 16)
  // The data is checked as the words that end at `head` and at `width`.
  std::uint32_t head = 0;
  std::uint64_t head_lanes = 0, tail_lanes = 0;
  std::vector<FieldCheck> valued;  // the fields with a range or labels
};

// The plan of a form of a catalog command (commands() holds every command a
// decode can find); an empty plan for anything else. Built once per form.
const FormPlan& plan_of(const CommandSpec& cmd, const FormSpec& form);

// The eight bytes that end at p (the frame's own: every header puts at least
// eight bytes before the data).
inline std::uint64_t word_before(const char* p) noexcept {
  std::uint64_t x;
  std::memcpy(&x, p - 8, 8);
  return x;
}

// The lanes of x (bytes below 0x80) whose byte lies in [lo, hi], as their
// top bit.
inline std::uint64_t lanes_in(std::uint64_t x, unsigned lo, unsigned hi) noexcept {
  return (x + kOnes * (0x80 - lo)) & ~(x + kOnes * (0x7F - hi)) & kTops;
}

// True when every lane of `lanes` holds 0-9 or A-F.
inline bool hex_lanes(std::uint64_t x, std::uint64_t lanes) noexcept {
  return ((lanes_in(x, '0', '9') | lanes_in(x, 'A', 'F')) & lanes) == lanes && (x & lanes) == 0;
}

}  // namespace top::detail
