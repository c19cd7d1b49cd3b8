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
  RunCommand run(app);
  FuzzCommand fuzz(app);
  GenerateCommand generate(app);
  ModelsCommand models(app);
  ValidateCommand validate(app);
  if (int rc = topkit::cli::parse(app, argc, argv); rc >= 0) return rc;
  return topkit::cli::run_selected(kTool, {&run, &fuzz, &generate, &models, &validate});
}
