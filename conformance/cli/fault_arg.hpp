// The one check of a fault list's names (topsim --fault, topconf
// --sim-fault): each name through the shared layer's one_of, as --model
// is, so an unknown fault is "TOOL: error: OPTION NAME: not one of drop,
// delay, ...", exit 2. The values are topsim::parse_faults' to check.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "sim/faults.hpp"
#include "topkit/cli.hpp"

namespace topsim::cli {

// False after the message when a name of `spec` ("drop=0.1,no-swap") is
// not one of topsim's faults.
inline bool fault_names_valid(const std::string& tool, const std::string& option,
                              std::string_view spec) {
  const std::vector<std::string> kinds(topsim::fault_names().begin(), topsim::fault_names().end());
  while (!spec.empty()) {
    const std::string_view item = spec.substr(0, spec.find(','));
    spec.remove_prefix(std::min(spec.size(), item.size() + 1));
    if (!item.empty() &&
        !topkit::cli::one_of(tool, option, std::string(item.substr(0, item.find('='))), kinds))
      return false;
  }
  return true;
}

}  // namespace topsim::cli
