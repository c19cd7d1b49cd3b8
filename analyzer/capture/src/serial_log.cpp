// A serial log of any format: the reader of its format, and read errors.
#include <cerrno>
#include <cstring>

#include "capture/input.hpp"
#include "log_reader.hpp"
#include "readers.hpp"
#include "serial_logs.hpp"

namespace topdump {

bool read_serial_log(Input& input, Format f, CaptureSink& a, std::string& error) {
  const std::string& path = input.name;
  if (f == Format::saleae && !make_seekable(input, error)) return false;
  LineReader r(input.file);
  switch (f) {
    case Format::raw:
      raw_log(path, r.in, a);
      break;
    case Format::socat:
      socat_log(path, r, a);
      break;
    case Format::saleae:
      saleae_log(path, input.file, r, a);
      break;
    case Format::lines:
      lines_log(path, r, a);
      break;
    default:
      error = path + ": not a serial log format";
      return false;
  }
  if (std::ferror(input.file)) {
    error = path + ": read error: " + std::strerror(errno);
    return false;
  }
  return true;
}

}  // namespace topdump
