// The two paths of parse_frame, apart: parse_frame accepts the common clean
// frame in one pass and leaves the rest to the general parse, and the result
// is the same either way. The general parse alone is for the tests and
// fuzzers that compare the two (tests/frame_test.cpp, fuzz/fuzz_frame.cpp),
// not a choice for callers of the API.
#pragma once

#include <string_view>

#include "top/frame.hpp"

namespace top::detail {

// parse_frame without its one-pass path for the common clean frame.
void parse_frame_general(std::string_view bytes, bool at_end, const ParseOptions& opts,
                         ParseResult& out);

}  // namespace top::detail
