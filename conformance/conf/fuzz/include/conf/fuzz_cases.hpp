// topconf fuzz's cases: indexed, reproducible datagrams generated from the
// library's catalog (every identifier and form of a model with boundary and
// out-of-range values, enum values and the one past, wrong and lying
// lengths, the four headers, checksum variants, framing, binary data with
// '#', oversized frames, unknown identifiers, wrong addresses, control
// characters), then seeded mutations of those. Pure: no I/O.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "conf/matrix.hpp"
#include "top/top.hpp"

namespace topconf {

// What the document promises for a case (as the matrix's levels say).
enum class Promise : std::uint8_t {
  none,     // nothing: only the form of the replies is checked
  answer,   // an answer with the request's identifier (echo or data)
  error,    // ERE (SkyDroid 2.3.2) or silence; not an answer with the identifier
  silence,  // every frame fails its checksum: no answer at all
};
std::string_view to_string(Promise p) noexcept;

struct FuzzCase {
  std::uint64_t index = 0;
  std::string family;  // "value", "checksum", ..., "mutation"
  std::string name;    // what the case is: "GAY w yaw max+1"
  std::string bytes;   // one datagram (one write on a stream link)
  Promise promise = Promise::none;
  Level level = Level::may;  // the matrix's level of the promise
  std::string ident;         // the identifier of its first frame ("" if none)
  std::size_t frames = 0;    // frames the library's stream decoder finds
  std::string addresses;     // source and destination of each frame ("UGUD")
  bool open_end = false;     // ends inside a frame: a stream link waits for
                             // the device to give up on it (20 ms quiet)
  bool mutated = false;
  std::uint64_t base = 0;  // mutations: the catalog case mutated
  bool repaired = false;   // mutations: lengths and checksums rewritten
};

class CaseSource {
 public:
  // `client`: the client address of the link (U, or P for Topotek on the
  // network). `matrix` gives the levels (nullptr: every promise is must).
  CaseSource(top::Model model, char client, std::uint64_t seed, const Matrix* matrix);
  // Cases below this index come from the catalog; the rest are mutations.
  std::uint64_t catalog_cases() const noexcept { return base_.size(); }
  // The case at `index`: the same bytes for the same model, client, seed
  // and index, whatever was generated before.
  FuzzCase at(std::uint64_t index) const;
  // The promise of arbitrary bytes, judged as for the generated cases.
  void judge(FuzzCase& c) const;

 private:
  void add(std::string family, std::string name, std::string bytes);
  void add_global();
  void add_form(const top::CommandSpec& c, const top::FormSpec& form);
  void add_values(const top::CommandSpec& c, const top::FormSpec& form, top::Header h,
                  const std::string& tag, const std::string& ex);
  Level level_for(std::string_view ident, char control, std::string_view tag) const;
  top::Model model_;
  top::Dialect dialect_;
  char client_;
  std::uint64_t seed_;
  const Matrix* matrix_;
  std::vector<FuzzCase> base_;
};

// The deterministic byte mutator: 1-4 edits (bit flip, byte set, insert,
// delete, duplicate a run, insert '#', CR/LF or a header) drawn from
// `rng_seed`. libFuzzer's LLVMFuzzerMutate only links into a libFuzzer
// binary, so this stands in for it; the repair pass is fuzz/mutator.hpp's.
std::string mutate(std::string bytes, std::uint64_t rng_seed, bool repair);

}  // namespace topconf
