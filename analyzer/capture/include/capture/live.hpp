// Live inputs: an interface through libpcap, serial ports through Asio
// (library topdump_capture_live: the fuzz targets link neither).
#pragma once

#include <atomic>
#include <chrono>
#include <string>
#include <vector>

#include "capture/read.hpp"
#include "capture/sink.hpp"

namespace topdump {

// Live capture on an interface with an optional BPF filter until `stop` is
// set (SIGINT). Returns false with `error` (and `permission` when the cause
// is a lack of capture privileges) when the capture cannot start.
bool capture_live(const std::string& iface, const std::string& bpf, CaptureSink& a,
                  const SourceOptions& o, const std::atomic<bool>& stop, std::string& error,
                  bool& permission);

// How long a live serial line must be quiet before a frame held to see
// whether CR/LF follows is released (a CR/LF within it belongs to the
// frame; an FTDI adapter's default latency timer is 16 ms).
inline constexpr std::chrono::milliseconds kSerialQuiet{50};

// Reads one serial device (one tap: frames go from the device's name to
// "peer") or two (two taps of one UART, one per direction: one
// conversation, each device named for the direction it taps) at `baud`
// (8N1) until `stop` is set.
bool read_serial_ports(const std::vector<std::string>& devices, unsigned baud, CaptureSink& a,
                       const std::atomic<bool>& stop, std::string& error);

}  // namespace topdump
