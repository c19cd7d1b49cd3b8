// How topdump shows a frame to people: the field tree and finding lines.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "top/top.hpp"

namespace topdump {

// Frame-level and catalog-level findings together, ordered by offset.
std::vector<const top::Finding*> all_findings(const top::Frame& f, const top::Decoded& d);
// Highest severity of all findings (info when none).
top::Severity worst(const top::Frame& f, const top::Decoded& d);

// Human name of an address char: "U (UART/UDP client)".
std::string address_name(char a);

// The field tree: header, addresses, command, each field with its value,
// unit and byte offset, the checksum, each finding with code and offset.
std::string frame_tree(const top::Frame& f, const top::Decoded& d);
// One line per finding: "  error   bad-checksum @12: checksum 00, expected 3E".
std::string finding_line(const top::Finding& f);

}  // namespace topdump
