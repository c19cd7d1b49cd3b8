// The session's counting stage: frames per identifier and findings per
// code, counted as frames go by and folded into Stats (per_ident,
// per_code) only when asked. Fixed state: a capture uses a handful of
// identifiers, so frames per identifier sit in pages of the identifier
// slots, each allocated at the first frame counted in it (docs/perf:
// "ident pages").
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>

#include "findings/afindings.hpp"
#include "session/stats.hpp"
#include "top/catalog.hpp"
#include "top/findings.hpp"

namespace topdump {

// The identifier as a 24-bit key, and back as display text.
inline std::uint32_t pack_ident(std::string_view id) noexcept {
  std::uint32_t k = 0;
  for (std::size_t i = 0; i < 3 && i < id.size(); ++i)
    k |= static_cast<std::uint32_t>(static_cast<unsigned char>(id[i])) << (8 * i);
  return k;
}
std::string unpack_ident(std::uint32_t k);

class Counters {
 public:
  void finding(top::FindingCode c) noexcept { ++codes_[static_cast<std::size_t>(c)]; }
  void note(ACode c) noexcept { ++acodes_[static_cast<std::size_t>(c)]; }
  std::uint64_t notes(ACode c) const noexcept { return acodes_[static_cast<std::size_t>(c)]; }
  // A frame of identifier `id` (3 chars, any bytes).
  void ident(const char id[3]) {
    if (const int i = top::ident_index(id); i >= 0) {
      const auto slot = static_cast<std::size_t>(i);
      auto& page = pages_[slot / kPage];
      if (!page) allocate(page);
      ++page[slot % kPage];
    } else {
      ++other_[pack_ident(std::string_view(id, 3))];
    }
  }
  // Frames per identifier and findings per code into `s`.
  void materialize(Stats& s) const;

 private:
  // Pages of 256 slots (2 KB), zeroed by the allocator (calloc): a
  // handful of frames pays for a page or two, not 373 KB of zeroes (the fuzz
  // targets build an analyzer per input; under ASan a page is a heap block,
  // not a fresh mmap); a power of two, so a slot's page is a shift
  // (docs/perf/decisions.md, "Frames counted per identifier"; 2 KB, not 16:
  // docs/perf/fuzz-speed.md, "Issue 48: the per-conversation cost").
  static constexpr std::size_t kPage = std::size_t{1} << 8;
  struct FreeDeleter {
    void operator()(std::uint64_t* p) const noexcept;
  };
  using Page = std::unique_ptr<std::uint64_t[], FreeDeleter>;
  static void allocate(Page& page);
  std::array<std::uint64_t, top::finding_code_count> codes_{};
  std::array<std::uint64_t, acode_count> acodes_{};
  std::array<Page, (top::ident_slots + kPage - 1) / kPage> pages_;
  std::unordered_map<std::uint32_t, std::uint64_t> other_;  // identifiers of other chars
};

// The latency stage: a histogram per identifier of the requests answered.
// A capture pairs a handful of identifiers, so a linear search of their
// keys, with the last index found per hashed slot, beats hashing
// (docs/perf/decisions.md, "Latency tables").
class LatencyTable {
 public:
  Latency& of(std::uint32_t key);
  // Per identifier's display text into `out`.
  void materialize(std::map<std::string, Latency>& out) const;

 private:
  std::vector<std::uint32_t> keys_;
  std::vector<Latency> values_;           // values_[i] is keys_[i]'s
  std::array<std::uint32_t, 64> hint_{};  // 1 + index into values_, 0: none
};

}  // namespace topdump
