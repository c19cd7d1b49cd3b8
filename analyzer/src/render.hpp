// How topdump shows a frame: a field tree for people, JSON for programs.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "top/top.hpp"

namespace topdump {

using json = nlohmann::ordered_json;

// Frame-level and catalog-level findings together, ordered by offset.
std::vector<const top::Finding*> all_findings(const top::Frame& f, const top::Decoded& d);
// Highest severity of all findings (info when none).
top::Severity worst(const top::Frame& f, const top::Decoded& d);

// Human name of an address char: "U (UART/UDP client)".
std::string address_name(char a);

// The JSON object of one frame with the documented keys (docs/topdump-json.md).
json frame_json(const top::Frame& f, const top::Decoded& d);
// The JSON object of a run of bytes that belong to no frame.
json garbage_json(const top::StreamItem& g);

// The field tree: header, addresses, command, each field with its value,
// unit and byte offset, the checksum, each finding with code and offset.
std::string frame_tree(const top::Frame& f, const top::Decoded& d);
// One line per finding: "  error   bad-checksum @12: checksum 00, expected 3E".
std::string finding_line(const top::Finding& f);

}  // namespace topdump
