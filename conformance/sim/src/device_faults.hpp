// Parsing the device faults of topsim --fault (sim/device.hpp DeviceFaults);
// private to sim/ (faults.cpp asks it for the names it does not know).
#pragma once

#include <string>
#include <string_view>

#include "sim/device.hpp"

namespace topsim::detail {

enum class Parsed { not_mine, ok, bad };

// Parses the fault `name` with `value` (`has_value`: an '=' was given) into
// `out`: not_mine for a name that is not a device fault, bad with `why`.
Parsed parse_device_fault(std::string_view name, bool has_value, std::string_view value,
                          DeviceFaults& out, std::string& why);

}  // namespace topsim::detail
