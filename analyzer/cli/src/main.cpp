// topdump: decode and diagnose TOP gimbal-camera traffic. One file per
// subcommand (<name>_cmd.cpp).
#include "commands.hpp"
#include "topkit/cli.hpp"

int main(int argc, char** argv) {
  using namespace topdump;
  CLI::App app{"topdump: decode and diagnose TOP (SkyDroid/Topotek gimbal camera) traffic"};
  topkit::cli::setup_app(app, kTool);
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 no error finding, 1 an error finding or a warning diagnosis (the field "
      "failures of docs/DIAGNOSES.md: silent-device, stream-stalled, clock-offset...), 2 "
      "unreadable input, a failed write or bad usage.\nEach subcommand's --help lists its options "
      "and examples; man "
      "topdump has them all.");
  // in this order in --help
  const std::unique_ptr<topkit::cli::Subcommand> commands[] = {
      read_command(app),   stats_command(app),  frame_command(app),    live_command(app),
      serial_command(app), report_command(app), wireshark_command(app)};
  if (int rc = topkit::cli::parse(app, argc, argv); rc >= 0) return rc;
  return topkit::cli::run_selected(kTool, commands);
}
