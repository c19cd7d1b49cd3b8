// topdump: decode and diagnose TOP gimbal-camera traffic.
#include <iostream>
#include <vector>

#include "commands.hpp"
#include "wireshark.hpp"

int main(int argc, char** argv) {
  CLI::App app{"topdump: decode and diagnose TOP (SkyDroid/Topotek gimbal camera) traffic"};
  app.require_subcommand(1);
  std::vector<topdump::Run> runs;
  runs.push_back(topdump::add_read_command(app));
  runs.push_back(topdump::add_stats_command(app));
  runs.push_back(topdump::add_frame_command(app));
  runs.push_back(topdump::add_live_command(app));
  runs.push_back(topdump::add_serial_command(app));
  runs.push_back(topdump::add_report_command(app));
  runs.push_back(topdump::add_wireshark_command(app));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  for (auto& run : runs) {
    int rc = run();
    if (rc >= 0) return rc;
  }
  return 2;
}
