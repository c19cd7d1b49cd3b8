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
  const auto run = run_command(app);
  const auto fuzz = fuzz_command(app);
  const auto generate = generate_command(app);
  const auto models = models_command(app);
  const auto validate = validate_command(app);
  const auto drivers = drivers_command(app);
  const auto table = table_command(app);
  const auto drive = drive_command(app);
  if (int rc = topkit::cli::parse(app, argc, argv); rc >= 0) return rc;
  return topkit::cli::run_selected(
      kTool, {run.get(), fuzz.get(), generate.get(), models.get(), validate.get(), drivers.get(),
              table.get(), drive.get()});
}
