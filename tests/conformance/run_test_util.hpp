// Helpers of the tests that read a topconf run's results.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "conf/runner.hpp"

// The result of case `id` (its stable ID); throws when the run has none.
inline const topconf::CaseResult& find_case(const topconf::RunResult& r, std::string_view id) {
  for (const auto& c : r.cases)
    if (c.spec->id == id) return c;
  throw std::runtime_error("no case " + std::string(id));
}
