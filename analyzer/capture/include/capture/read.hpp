// Reading inputs to the end: capture files, serial logs, two logs merged.
#pragma once

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "capture/input.hpp"
#include "capture/sink.hpp"

namespace topdump {

// The ports of top::known_ports() of one transport.
std::set<std::uint16_t> known_ports(bool tcp);

struct SourceOptions {
  std::set<std::uint16_t> udp_ports = known_ports(false);
  std::set<std::uint16_t> tcp_ports = known_ports(true);
  // Called now and then with (bytes read, total bytes) for a progress bar.
  std::function<void(std::uint64_t, std::uint64_t)> progress;
  // Called once per input when its format (and link type) is known, before
  // its first record.
  std::function<void(const InputInfo&)> on_input;
  // Called with each packet of a pcap/pcapng source before it is dissected:
  // (link type, time, captured bytes, length on the wire, record); read -w.
  std::function<void(int, std::int64_t, std::string_view, std::uint32_t, std::uint64_t)> packet;
};

// Reads a capture file of any supported format into the sink. Returns
// false and sets `error` when the file cannot be read at all (exit 2);
// problems inside the file become findings.
// A damaged capture (damaged_capture()), a --format that the file is not
// and a cut file header are such errors. `info`, when given, says what was
// read.
bool read_file(const std::string& path, Format format, CaptureSink& a, const SourceOptions& o,
               std::string& error, InputInfo* info = nullptr);
bool read_input(Input& in, Format format, CaptureSink& a, const SourceOptions& o,
                std::string& error, InputInfo* info = nullptr);

// The most bytes read_merged holds to merge two logs.
inline constexpr std::size_t kMaxMergeBytes = std::size_t{256} << 20;

// Two serial logs with times, each one tap (one direction) of one UART,
// merged by time into one conversation: each log's frames go from its name
// to the other's. Captures and raw dumps (no times) are errors.
bool read_merged(const std::vector<std::string>& paths, Format format, CaptureSink& a,
                 const SourceOptions& o, std::string& error, std::vector<InputInfo>* infos);

}  // namespace topdump
