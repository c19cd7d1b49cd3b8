// The tree's own decode of many frames: through a DecodeCache, which
// remembers what each frame shape decided (docs/perf/decisions.md, "Decode
// shape cache"), and with the session's prefilter
// (top/detail/prefilter.hpp). A speed device, not the library's contract:
// the results are top::decode()'s.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "top/decode.hpp"

namespace top::detail {

struct ShapeSlot;    // protocol/src/shape_slot.hpp
struct CacheAccess;  // protocol/src/shape_slot.hpp

// Remembers what decode() without detail found for a frame's shape: its
// dialect, role, identifier, header, lengths and control decide the command,
// the form and the findings that follow from them, so a frame of a shape
// seen before skips the catalog lookups and goes straight to its data. The
// results are the same with or without it (tested, and compared by the
// decode fuzzers). One per thread; 128 slots by default (a few kilobytes),
// rounded up to a power of two, allocated at the first lookup (a cache that
// decode() never uses, as with detail, costs nothing).
class DecodeCache {
 public:
  explicit DecodeCache(std::size_t slots = 128);
  ~DecodeCache();
  DecodeCache(const DecodeCache&) = delete;
  DecodeCache& operator=(const DecodeCache&) = delete;

  // Shapes looked up that their slot did not hold (first sight or evicted).
  std::uint64_t misses() const noexcept { return misses_; }

 private:
  friend struct CacheAccess;
  std::unique_ptr<ShapeSlot[]> slots_;  // count_ of them, from the first lookup
  std::size_t count_ = 0;
  std::uint64_t misses_ = 0;
  unsigned shift_ = 32;  // a slot is the top log2(slots) bits of a 32-bit hash
};

// top::decode(frame, opts, out), through `cache` when `opts.detail` is false
// (messages are not remembered; with detail, or null, no cache is used).
// Returns may_matter_to_diagnoses(frame.ident) (top/detail/prefilter.hpp),
// the shape's like the command: the session asks it of every frame.
bool decode(const Frame& frame, const DecodeOptions& opts, DecodeCache* cache, Decoded& out);

}  // namespace top::detail
