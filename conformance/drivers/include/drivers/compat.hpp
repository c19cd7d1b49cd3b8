// A driver's compatibility with a device: the matrix of a profile's needs,
// and the verdict read from its run (docs/COMPAT.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "conf/matrix.hpp"
#include "conf/runner.hpp"
#include "drivers/profile.hpp"

namespace drivers {

// The case id of a need: driver/<profile>/<need>.
std::string case_id(const Profile& p, const Need& n);

// The matrix of `p`'s needs for `model` (topconf-matrix-1 JSON, as `topconf
// generate` writes): one case per need, level must, should or may (info).
nlohmann::ordered_json driver_matrix_json(const Profile& p, top::Model model);
// The same, loaded (load_matrix: validated, regexes compiled).
topconf::LoadResult driver_matrix(const Profile& p, top::Model model);

// One need's outcome.
struct NeedResult {
  const Need* need = nullptr;
  topconf::Verdict verdict = topconf::Verdict::error;
  bool served = false;  // pass, non-strict or (flaky) pass
  std::string reason;   // the case's reason
  std::string outcome;  // "<reasoning>; this device: <reason>: <lost>"
};

struct Compatibility {
  enum class Level : std::uint8_t { compatible, without, incompatible, unreachable };
  const Profile* profile = nullptr;
  top::Model model = top::Model::unknown;
  Level level = Level::unreachable;
  std::vector<std::string> features;  // should needs not served
  std::vector<std::string> reasons;   // must needs not served: "<feature>: <lost>"
  std::vector<NeedResult> needs;
  // "compatible", "compatible without: a, b", "incompatible: r1; r2",
  // "unreachable: why".
  std::string text() const;
  // 0 compatible (with or without features), 1 incompatible, 2 unreachable.
  int exit_code() const noexcept;
};
std::string_view to_string(Compatibility::Level l) noexcept;

// The verdict of `run`, a run of driver_matrix(p, model).
Compatibility assess(const Profile& p, const topconf::RunResult& run);

// The `compatibility` object of topconf's JSON.
nlohmann::json to_json(const Compatibility& c);
// A profile as `topconf drivers --json` lists it: link, cadence, sends,
// parsing, needs, each with its source.
nlohmann::json to_json(const Profile& p);

}  // namespace drivers
