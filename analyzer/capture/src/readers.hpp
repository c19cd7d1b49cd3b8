// The readers behind read_input() (capture's own header).
#pragma once

#include <string>

#include "capture/input.hpp"
#include "capture/read.hpp"
#include "capture/sink.hpp"

namespace topdump {

// A pcap or pcapng file (`format`), described by `what`.
bool read_capture_file(Input& in, Format format, CaptureSink& a, const SourceOptions& o,
                       std::string& error, InputInfo what, InputInfo* info);

// A serial log of `f` (raw, socat, saleae or lines).
bool read_serial_log(Input& in, Format f, CaptureSink& a, std::string& error);

}  // namespace topdump
