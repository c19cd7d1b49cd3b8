// The checksum-aware mutator: libFuzzer's own mutation, then a repair pass
// that rewrites the length field and the checksum of every frame in the
// output, so most mutants get past the checksum and reach the decoder. About
// one output in eight is left unrepaired (chosen from libFuzzer's seed, so a
// run is reproducible with -seed=N) to keep the reject paths covered.
//
// Include this header in exactly one translation unit of a target. Set
// TOPKIT_FUZZ_NO_MUTATOR=1 in the environment to measure the same binary
// with plain libFuzzer mutation (the README's comparison does that).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "top/detail/repair.hpp"

namespace topfuzz {

// The repair pass itself is the library's (top/detail/repair.hpp): topconf
// fuzz repairs its mutants the same way.
using top::detail::repair_frames;

// True for the seeds whose output stays unrepaired (about 1 in 8).
inline bool leave_unrepaired(unsigned int seed) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull;  // splitmix64 finaliser
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (z & 7) == 0;
}

inline bool mutator_disabled() {
  static const bool off = [] {
    const char* v = std::getenv("TOPKIT_FUZZ_NO_MUTATOR");
    return v != nullptr && v[0] != '\0' && v[0] != '0';
  }();
  return off;
}

}  // namespace topfuzz

#ifdef TOPKIT_LIBFUZZER
extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size,
                                               std::size_t max_size, unsigned int seed) {
  std::size_t n = LLVMFuzzerMutate(data, size, max_size);
  if (topfuzz::mutator_disabled() || topfuzz::leave_unrepaired(seed)) return n;
  topfuzz::repair_frames(data, n);
  return n;
}
#endif
