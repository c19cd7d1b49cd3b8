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

// --dialect and --model ("auto" or a name) as one setting; false, with a
// message, when either is unknown or the model speaks the other dialect.
inline bool dialect_and_model(const std::string& dialect, const std::string& model, top::Dialect& d,
                              top::Model& m, std::string& err) {
  auto dd = top::dialect_from_string(dialect);
  auto mm = top::model_from_string(model);
  if (!dd || !mm) {
    err = "bad --dialect or --model";
    return false;
  }
  if (*mm != top::Model::unknown && *dd != top::Dialect::unknown && top::dialect_of(*mm) != *dd) {
    err = "model " + model + " speaks " + std::string(top::to_string(top::dialect_of(*mm))) +
          ", not " + dialect;
    return false;
  }
  d = *dd;
  m = *mm;
  return true;
}

Run add_frame_command(CLI::App& app);
Run add_read_command(CLI::App& app);
Run add_stats_command(CLI::App& app);
Run add_live_command(CLI::App& app);
Run add_serial_command(CLI::App& app);
Run add_report_command(CLI::App& app);
Run add_wireshark_command(CLI::App& app);

}  // namespace topdump
