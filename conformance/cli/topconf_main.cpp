// topconf: runs a conformance matrix against a TOP device (or an in-process
// topsim) and reports per case; generates and validates matrices. One file
// per subcommand (topconf_<name>.cpp).
#include "commands.hpp"
#include "topkit/cli.hpp"
#include "topkit/log.hpp"

int main(int argc, char** argv) {
  using namespace topconf::cli;
  // Messages go to stderr ("topconf: error: ..."); stdout carries results.
  topkit::cli::use_stderr_log(kTool);
  CLI::App app{"topconf: conformance runner for the TOP gimbal-camera protocol"};
  topkit::cli::setup_app(app, kTool);
  app.require_subcommand(1);
  // in this order in --help
  return topkit::cli::run_tool(app, argc, argv,
                               {run_command, fuzz_command, generate_command, models_command,
                                validate_command, drivers_command, table_command, drive_command});
}
