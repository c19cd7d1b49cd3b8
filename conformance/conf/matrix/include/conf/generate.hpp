// Generates a model's default matrix from the catalog (one source of
// truth): the files in conformance/matrices/ are its output, written by
// `topconf generate` (see conformance/matrices/regenerate.sh).
#pragma once

#include <nlohmann/json.hpp>

#include "top/top.hpp"

namespace topconf {

nlohmann::ordered_json generate_matrix(top::Model model);

}  // namespace topconf
