// The one check of a --model value, from the catalog's model list
// (topkit/cli.hpp's one_of): topsim and topconf.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "top/top.hpp"
#include "topkit/cli.hpp"

namespace topkit::cli {

// The catalog's models ("c10", ..., "sip").
inline std::vector<std::string> model_names() {
  std::vector<std::string> v;
  for (top::Model m : top::all_models()) v.emplace_back(top::to_string(m));
  return v;
}

// The model `value` names, or none with "TOOL: error: --model VALUE: not
// one of c10, ...".
inline std::optional<top::Model> model_arg(const std::string& tool, const std::string& value,
                                           const std::string& option = "--model") {
  if (!one_of(tool, option, value, model_names())) return std::nullopt;
  return top::model_from_string(value);
}

}  // namespace topkit::cli
