// topdump: decode and diagnose TOP gimbal-camera traffic.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "topkit/cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"topdump: decode and diagnose TOP (SkyDroid/Topotek gimbal camera) traffic"};
  topkit::cli::setup_app(app, "topdump");
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 no error finding, 1 an error finding, 2 unreadable input, a failed "
      "write or bad usage.\nEach subcommand's --help lists its options and examples; man "
      "topdump has them all.");
  std::vector<topdump::Run> runs;
  runs.push_back(topdump::add_read_command(app));
  runs.push_back(topdump::add_stats_command(app));
  runs.push_back(topdump::add_frame_command(app));
  runs.push_back(topdump::add_live_command(app));
  runs.push_back(topdump::add_serial_command(app));
  runs.push_back(topdump::add_report_command(app));
  runs.push_back(topdump::add_wireshark_command(app));
  if (int rc = topkit::cli::parse_or_exit(app, argc, argv); rc >= 0) return rc;
  int rc = 2;
  for (auto& run : runs) {
    rc = run();
    if (rc >= 0) break;
  }
  return topkit::cli::close_stdout("topdump", rc < 0 ? 2 : rc);
}
