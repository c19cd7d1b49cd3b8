// topconf fuzz's outputs: JSON Lines of every case, JUnit XML with one
// testcase per failure class, a self-contained HTML report in the style of
// `topconf run`'s, and the console summary.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "conf/fuzz.hpp"

namespace topconf {

// One JSON Lines record per case: {"index", "family", "name", "bytes"
// (top::escape), "promise", "level", "mutated", "base", "repaired",
// "verdict" ("pass" or a failure class), "reason", "answers", "start_us",
// "latency_us"}.
nlohmann::json to_json(const FuzzCaseResult& r);
// The session line that starts a --json file: {"session": "topconf-fuzz-1",
// "model", "seed", "target", "catalog_cases", "started_at"}; --resume reads it.
nlohmann::json session_json(const FuzzResult& r);
// A failure with its minimisation: {"failure": class, "index", ...}.
nlohmann::json to_json(const FuzzFailure& f);
// The summary line that ends the file: {"summary": {...}}.
nlohmann::json summary_json(const FuzzResult& r);
void write_junit(std::ostream& os, const FuzzResult& r);
void write_html(std::ostream& os, const FuzzResult& r);
void write_console(std::ostream& os, const FuzzResult& r);
// "case 123 (family: name): class: reason; minimised: ..." for the console.
std::string failure_line(const FuzzFailure& f);

}  // namespace topconf
