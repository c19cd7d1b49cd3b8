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
  return topkit::cli::run_tool(app, argc, argv,
                               {read_command, stats_command, frame_command, live_command,
                                serial_command, report_command, wireshark_command});
}
