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

// FUZZ_CHECK(cond, detail): abort with `detail` (a std::string expression,
// evaluated only on failure) when `cond` is false.
#define FUZZ_CHECK(cond, detail)                                       \
  do {                                                                 \
    if (!(cond)) ::topfuzz::fail(__FILE__, __LINE__, #cond, (detail)); \
  } while (0)
