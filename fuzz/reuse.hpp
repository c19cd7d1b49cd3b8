// Results a target keeps across inputs and parses or decodes into (the
// forms topdump's loops use), so that their buffers are reused instead of
// allocated and freed on every input: under ASan an allocation and its free
// cost more than most parses.
//
// They get room for any input of the target up front. A buffer that grew
// while an input ran would look to libFuzzer like a leak (more mallocs than
// frees in the run), and libFuzzer then runs that input again under
// LeakSanitizer's full scan, milliseconds each time.
#pragma once

#include <cstddef>
#include <string>
#include <tuple>
#include <vector>

#include "check.hpp"
#include "top/top.hpp"

namespace topfuzz {

// Room enough for the findings and fields of any frame a target builds.
inline constexpr std::size_t kRoomFindings = 64;
// (fields: an ODR's one-byte length holds a count and 21 records of 6: 127)
inline constexpr std::size_t kRoomFields = 128;

inline top::ParseResult reused_parse_result() {
  top::ParseResult r;
  r.frame.raw.reserve(capped(std::size_t{1} << 17));
  r.frame.findings.reserve(kRoomFindings);
  return r;
}

inline top::Decoded reused_decoded() {
  top::Decoded d;
  d.fields.reserve(kRoomFields);
  d.findings.reserve(kRoomFindings);
  return d;
}

// What a result holds on the heap beyond its reserved room (the texts of
// findings and fields) is freed when the input ends: libFuzzer counts an
// input's mallocs and frees, and a text kept until the next input's parse
// would count as a leak of this one.
inline void release(top::ParseResult& r) {
  r.frame.findings.clear();
  r.error.message = std::string();
}
inline void release(top::Decoded& d) {
  d.fields.clear();
  d.findings.clear();
}
template <class T>
void release(std::vector<T>& v) {
  v.clear();
}
// A stream item's buffers circulate through its decoder (next() swaps them
// in and out), so they are kept; only the texts are freed.
inline void release(top::StreamItem& it) {
  it.frame.findings.clear();
  it.finding.message = std::string();
}

// Releases the given results when it goes out of scope, at every return of
// the target.
template <class... R>
class ReleaseAtEnd {
 public:
  explicit ReleaseAtEnd(R&... r) : results_(r...) {}
  ReleaseAtEnd(const ReleaseAtEnd&) = delete;
  ReleaseAtEnd& operator=(const ReleaseAtEnd&) = delete;
  ~ReleaseAtEnd() {
    std::apply([](auto&... x) { (release(x), ...); }, results_);
  }

 private:
  std::tuple<R&...> results_;
};

// A string for formatted values (append_value), as long as any input.
inline std::string reused_text() {
  std::string s;
  s.reserve(capped(std::size_t{1} << 17) * 4 + 256);  // \xNN per byte at most
  return s;
}

}  // namespace topfuzz
