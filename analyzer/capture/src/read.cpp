// Reading an input to the end: its format checked or detected, then the
// capture file or serial log reader.
#include "capture/read.hpp"

#include "magic.hpp"
#include "readers.hpp"
#include "top/top.hpp"

namespace topdump {

std::set<std::uint16_t> known_ports(bool tcp) {
  std::set<std::uint16_t> s;
  for (const top::PortSpec& p : top::known_ports())
    if (p.tcp == tcp) s.insert(p.port);
  return s;
}

bool read_file(const std::string& path, Format format, CaptureSink& a, const SourceOptions& o,
               std::string& error, InputInfo* info) {
  Input in;
  if (!open_input(path, in, error)) return false;
  return read_input(in, format, a, o, error, info);
}

bool read_input(Input& in, Format format, CaptureSink& a, const SourceOptions& o,
                std::string& error, InputInfo* info) {
  const std::string& path = in.name;
  const bool ng_magic = is_pcapng_magic(in.head);
  const bool pcap_magic = is_pcap_magic(in.head);
  if (format == Format::automatic) {
    if (auto why = damaged_capture(in.head)) {
      error = path + ": " + *why;
      return false;
    }
    format = detect_format(in.head);
  } else if ((format == Format::pcap || format == Format::pcapng) && !pcap_magic && !ng_magic) {
    error = path + ": offset 0: " +
            (in.head.size() < 4 ? "the file holds " + std::to_string(in.head.size()) + " bytes"
                                : "magic number " + hex32(in.head)) +
            ", not a " + std::string(to_string(format)) + " file";
    return false;
  } else if ((format == Format::pcap && ng_magic) || (format == Format::pcapng && pcap_magic)) {
    error = path + ": offset 0: --format " + std::string(to_string(format)) + " but this is a " +
            (ng_magic ? "pcapng" : "pcap") + " file";
    return false;
  }
  InputInfo what{path, format, {}};
  if (format != Format::pcap && format != Format::pcapng) {
    if (info) *info = what;
    if (o.on_input) o.on_input(what);
    return read_serial_log(in, format, a, error);
  }
  return read_capture_file(in, format, a, o, error, what, info);
}

}  // namespace topdump
