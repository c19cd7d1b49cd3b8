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

// The size of an input a target looks at. libFuzzer builds cut inputs to
// the -max_len given on the command line, else to the options' max_len
// (TOPKIT_FUZZ_MAX_LEN, from fuzz_<target>.options): libFuzzer cuts seeds
// the same way, but another engine may not read the options. Replay builds
// (ctest) take every input whole.
#ifdef TOPKIT_FUZZ_MAX_LEN
inline std::size_t& max_len() {
  static std::size_t n = TOPKIT_FUZZ_MAX_LEN;
  return n;
}
#endif

inline std::size_t capped(std::size_t size) {
#ifdef TOPKIT_FUZZ_MAX_LEN
  return size < max_len() ? size : max_len();
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

#ifdef TOPKIT_FUZZ_MAX_LEN
// Reads -max_len=N from libFuzzer's command line (see capped()); the last
// one given wins, as in libFuzzer.
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  for (int i = 1; i < *argc; ++i) {
    const std::string_view a = (*argv)[i];
    if (a.substr(0, 9) != "-max_len=") continue;
    const std::size_t n = std::strtoull(a.data() + 9, nullptr, 10);
    if (n > 0) topfuzz::max_len() = n;  // 0: libFuzzer picks, the options' cap stays
  }
  return 0;
}
#endif

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
