// Shared by the fuzz targets: a check that aborts with a message (libFuzzer
// then saves the input as a crash), and helpers to describe bytes.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace topfuzz {

[[noreturn]] inline void fail(const char* file, int line, const char* what,
                              const std::string& detail) {
  std::fprintf(stderr, "%s:%d: fuzz check failed: %s\n  %s\n", file, line, what, detail.c_str());
  std::fflush(stderr);
  std::abort();
}

// The size of an input a target looks at: in libFuzzer builds at most the
// options' max_len (TOPKIT_FUZZ_MAX_LEN, from fuzz_<target>.options), as
// libFuzzer cuts seeds to -max_len, in case an engine does not read the
// options; replay builds (ctest) take every input whole.
inline std::size_t capped(std::size_t size) {
#ifdef TOPKIT_FUZZ_MAX_LEN
  return size < std::size_t{TOPKIT_FUZZ_MAX_LEN} ? size : std::size_t{TOPKIT_FUZZ_MAX_LEN};
#else
  return size;
#endif
}

// Printable rendering of bytes for failure messages: \xNN for the rest.
inline std::string show(std::string_view s, std::size_t limit = 200) {
  std::string out;
  for (std::size_t i = 0; i < s.size() && i < limit; ++i) {
    auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7F && c != '\\') {
      out += static_cast<char>(c);
    } else {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02X", c);
      out += b;
    }
  }
  if (s.size() > limit) out += "...";
  return out;
}

}  // namespace topfuzz

#ifdef TOPKIT_LIBFUZZER
// ASan keeps freed blocks out of reuse until 256 MB more have been freed
// (its quarantine), so for the first 256 MB a target allocates every block
// is fresh memory and every 4 KiB of it a page fault: most of a 20 s run
// on the shared VM (a fault costs ~65 us there). Our inputs allocate well
// under 1 MB each, so 16 MB still keeps every block freed while an input
// runs out of reuse until it ends. ASAN_OPTIONS in the environment (as
// ClusterFuzzLite sets) override this.
extern "C" const char* __asan_default_options() { return "quarantine_size_mb=16"; }
#endif

// FUZZ_CHECK(cond, detail): abort with `detail` (a std::string expression,
// evaluated only on failure) when `cond` is false.
#define FUZZ_CHECK(cond, detail)                                       \
  do {                                                                 \
    if (!(cond)) ::topfuzz::fail(__FILE__, __LINE__, #cond, (detail)); \
  } while (0)
