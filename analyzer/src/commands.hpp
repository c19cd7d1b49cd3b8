// topdump subcommands. Each add_* registers its options on the app and
// returns the function that runs it once parsed, returning the exit status:
// 0 no error finding, 1 an error finding, 2 unreadable input or bad usage.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "top/catalog.hpp"

namespace topdump {

using Run = std::function<int()>;

// The values of --model: auto and every model of the catalog.
inline CLI::IsMember model_check() {
  std::vector<std::string> v{"auto"};
  for (top::Model m : top::all_models()) v.emplace_back(top::to_string(m));
  return CLI::IsMember(v);
}

Run add_frame_command(CLI::App& app);
Run add_read_command(CLI::App& app);
Run add_stats_command(CLI::App& app);
Run add_live_command(CLI::App& app);
Run add_serial_command(CLI::App& app);
Run add_report_command(CLI::App& app);

}  // namespace topdump
