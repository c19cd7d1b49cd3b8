// Raw serial dumps: the bytes one tap received, as they came.
#include <istream>
#include <vector>

#include "log_reader.hpp"
#include "serial_logs.hpp"

namespace topdump {

// A raw dump holds the bytes one tap received: one direction, named for
// the file, to the end that was not tapped ("peer").
void raw_log(const std::string& path, std::istream& in, CaptureSink& a) {
  Endpoint src = named(path), dst = named("peer");
  std::vector<char> buf(1 << 16);
  std::uint64_t off = 0;
  a.record(true);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    auto n = static_cast<std::size_t>(in.gcount());
    if (n == 0) break;
    a.chunk(kNoTime, Transport::serial, src, dst, std::string_view(buf.data(), n), 1, off);
    off += n;
  }
}

}  // namespace topdump
