// The grades of topconf drive (docs/DRIVE.md "Grades", as Autobahn
// grades a case) and the checks of each case.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drive/cases.hpp"
#include "drive/record.hpp"

namespace topconf::drive {

enum class Grade : std::uint8_t { pass, non_strict, informational, unimplemented, fail, error };
// "pass", "non-strict", "informational", "unimplemented", "fail", "error"
std::string_view to_string(Grade g) noexcept;
std::optional<Grade> grade_from_string(std::string_view s) noexcept;
// The exit status a run with these grades has: 2 with an error, 1 with a
// fail, else 0.
int exit_code_of(const std::vector<Grade>& grades) noexcept;

struct Check {
  std::string name;
  bool ok = false;
  std::string detail;
};

struct Verdict {
  Grade grade = Grade::pass;
  std::string reason;
  std::vector<Check> checks;
};

// Grades what a case saw. `model` for its identifiers; `setup` the case as
// it ran (its fault times).
Verdict grade_case(const CaseSpec& c, const CaseSetup& setup, top::Model model,
                   topsim::TransportKind link, const Record& r);

}  // namespace topconf::drive
