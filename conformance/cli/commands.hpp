// topconf's subcommands, one file each (topconf_<name>.cpp), in the one
// pattern of topkit/cli.hpp: options added in the constructor, run() when
// the command line chose it. And what they share: the matrix files.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "conf/fuzz.hpp"
#include "conf/matrix.hpp"
#include "topkit/cli.hpp"

namespace topconf::cli {

inline constexpr const char* kTool = "topconf";

// Where the default matrices are: $TOPCONF_MATRIX_DIR, else
// share/topkit/matrices relative to the topconf binary (installed, or the
// build tree's copy).
std::string matrix_dir();
// The whole file, or none.
std::optional<std::string> read_file(const std::string& path);
// Writes `path` with `f`; false with a message when it cannot.
bool write_output(const std::string& path, const std::function<void(std::ostream&)>& f);
// The --model and --matrix of run and fuzz: the matrix of `model_name`
// (`matrix_path`, or the default one, or one generated from the catalog),
// set to run as that model. Returns the exit status on failure (2).
std::optional<int> load_run_matrix(const std::string& model_name, const std::string& matrix_path,
                                   Matrix& out);

class RunCommand : public topkit::cli::Subcommand {
 public:
  explicit RunCommand(CLI::App& app);
  int run() override;

 private:
  std::string target_, model_name_, matrix_path_, json_out_, junit_out_, html_out_, pcap_out_,
      sim_faults_;
  std::vector<std::string> case_ids_, tags_, levels_;
  std::uint64_t seed_ = 0, sim_seed_ = 1;
  std::uint32_t retries_ = 0, timeout_ms_ = 0, settle_ms_ = 0;
  int bind_port_ = -1;
  bool no_color_ = false, quiet_ = false;
  CLI::Option *seed_opt_ = nullptr, *retries_opt_ = nullptr, *timeout_opt_ = nullptr,
              *settle_opt_ = nullptr;
};

class FuzzCommand : public topkit::cli::Subcommand {
 public:
  explicit FuzzCommand(CLI::App& app);
  int run() override;

 private:
  int run(const Matrix& matrix);
  std::optional<int> resume(top::Model model, FuzzOptions& o, bool& append);
  std::string model_name_, matrix_path_;
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

class GenerateCommand : public topkit::cli::Subcommand {
 public:
  explicit GenerateCommand(CLI::App& app);
  int run() override;

 private:
  std::string model_name_, out_;
};

class ModelsCommand : public topkit::cli::Subcommand {
 public:
  explicit ModelsCommand(CLI::App& app);
  int run() override;

 private:
  bool paths_ = false;
};

class ValidateCommand : public topkit::cli::Subcommand {
 public:
  explicit ValidateCommand(CLI::App& app);
  int run() override;

 private:
  std::vector<std::string> files_;
};

}  // namespace topconf::cli
