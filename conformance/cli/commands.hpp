// topconf's subcommands, one file each (topconf_<name>.cpp), in the one
// pattern of topkit/cli.hpp (a Subcommand, best an OwnSubcommand that holds
// only its own options): options added when it is made, run() when the
// command line chose it. And what they share: the matrix files.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <memory>
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

// The target of run and fuzz: a device, or an in-process topsim.
struct TargetArgs {
  std::string target;      // --target (run: empty for the in-process topsim)
  std::string sim_faults;  // --sim-fault
  std::uint64_t sim_seed = 1;
  int bind_port = -1;  // --bind
};

// The files run and fuzz write besides stdout.
struct OutputArgs {
  std::string json, junit, html, pcap;
};

// The subcommands, each defined in its file (topconf_<name>.cpp); main()
// adds them in its order.
topkit::cli::SubcommandFactory run_command, fuzz_command, generate_command, models_command,
    validate_command, drivers_command, table_command, drive_command;

}  // namespace topconf::cli
