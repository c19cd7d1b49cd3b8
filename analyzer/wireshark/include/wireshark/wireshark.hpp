// topdump wireshark: a Wireshark dissector (Lua) generated from the catalog.
#pragma once

#include <string>

namespace topdump {

// The whole of top.lua: the catalog's tables, then the fixed dissector.
std::string wireshark_lua();

}  // namespace topdump
