// topdump wireshark: the generated dissector (wireshark/) to stdout.
#include <iostream>
#include <string>

#include "commands.hpp"
#include "wireshark/wireshark.hpp"

namespace topdump {

Run add_wireshark_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "wireshark", "write top.lua, a Wireshark dissector generated from the catalog, to stdout");
  sub->footer(
      "Examples:\n"
      "  topdump wireshark > ~/.local/lib/wireshark/plugins/top.lua\n"
      "  tshark -X lua_script:top.lua -r captures/sample.pcap -V -Y top (docs/WIRESHARK.md)");
  return [sub]() -> int {
    if (!sub->parsed()) return -1;
    const std::string lua = wireshark_lua();
    std::cout << lua;
    std::cout.flush();
    return std::cout ? 0 : 2;
  };
}

}  // namespace topdump
