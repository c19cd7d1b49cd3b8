// The serial log formats (capture's own header): each reads its log to the
// end into the sink; a line that does not follow the format is a
// log-syntax note, and reading goes on.
#pragma once

#include <cstdio>
#include <istream>
#include <string>

#include "capture/sink.hpp"
#include "log_reader.hpp"

namespace topdump {

// A raw dump holds the bytes one tap received: one direction, named for
// the file, to the end that was not tapped ("peer").
void raw_log(const std::string& path, std::istream& in, CaptureSink& a);
// socat -v (text) and socat -x -v (hex) dumps.
void socat_log(const std::string& path, LineReader& r, CaptureSink& a);
// Saleae Logic 2 Async Serial export (`file` is scanned twice: seekable).
void saleae_log(const std::string& path, std::FILE* file, LineReader& r, CaptureSink& a);
// "<ISO time> <TX|RX> <frame>" lines.
void lines_log(const std::string& path, LineReader& r, CaptureSink& a);

}  // namespace topdump
