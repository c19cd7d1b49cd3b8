// topdump wireshark: a Wireshark dissector (Lua) generated from the catalog.
#pragma once

#include <string>

#include "commands.hpp"

namespace topdump {

// The whole of top.lua: the catalog's tables, then the fixed dissector.
std::string wireshark_lua();

Run add_wireshark_command(CLI::App& app);

}  // namespace topdump
