// `topconf fuzz`: the subcommand's options and what it does once topconf's
// main has loaded the model's matrix (the probe, its timeout and the levels).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "conf/matrix.hpp"

namespace topconf {

class FuzzCommand {
 public:
  // Adds the subcommand to `app`; --model and --matrix fill the variables
  // `topconf run` uses, so main loads the matrix the same way for both.
  FuzzCommand(CLI::App& app, std::string& model_name, std::string& matrix_path);
  bool selected() const { return sub_->parsed(); }
  // Runs the session; returns the exit status (0, 1, 2).
  int run(const Matrix& matrix);

 private:
  CLI::App* sub_;
  std::string target_, sim_faults_, resume_, restart_cmd_, json_, junit_, html_, pcap_;
  std::uint64_t seed_ = 1, sim_seed_ = 1, cases_ = 0, start_ = 0, end_ = 0;
  std::vector<std::uint64_t> only_;
  double duration_ = 0, rate_ = 0;
  std::uint32_t probe_every_ = 1, timeout_ms_ = 300, slow_ms_ = 1000, recover_ms_ = 3000;
  std::size_t window_ = 8, max_failures_ = 0;
  std::uint32_t probe_timeout_ms_ = 0;
  int bind_port_ = -1;
  bool no_minimise_ = false, quiet_ = false;
  CLI::Option *seed_opt_ = nullptr, *cases_opt_ = nullptr, *start_opt_ = nullptr,
              *end_opt_ = nullptr;
};

}  // namespace topconf
