// topdump wireshark: the generated dissector (wireshark/) to stdout.
#include <iostream>
#include <string>

#include "commands.hpp"
#include "wireshark/wireshark.hpp"

namespace topdump {

namespace {

struct Wireshark {
  static void declare(CLI::App& sub) {
    sub.footer(
        "Examples:\n"
        "  topdump wireshark > ~/.local/lib/wireshark/plugins/top.lua\n"
        "  tshark -X lua_script:top.lua -r captures/sample.pcap -V -Y top (docs/WIRESHARK.md)");
  }
  // run_selected checks that stdout took it all.
  static int run() {
    std::cout << wireshark_lua();
    return 0;
  }
};

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> wireshark_command(CLI::App& app) {
  return topkit::cli::make_subcommand<Wireshark>(
      app, "wireshark",
      "write top.lua, a Wireshark dissector generated from the catalog, to stdout");
}

}  // namespace topdump
