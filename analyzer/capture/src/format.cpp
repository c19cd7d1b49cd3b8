// Input formats: their names, and which one a file's first bytes are.
#include <cstring>

#include "capture/input.hpp"
#include "capture/time.hpp"
#include "log_reader.hpp"

namespace topdump {

namespace {
constexpr std::string_view kFormat[] = {"auto",   "pcap",  "raw",   "socat",
                                        "saleae", "lines", "pcapng"};
static_assert(std::size(kFormat) == static_cast<std::size_t>(Format::pcapng) + 1);
}  // namespace

std::optional<Format> format_from_string(std::string_view s) {
  for (std::size_t i = 0; i < std::size(kFormat); ++i)
    if (kFormat[i] == s) return static_cast<Format>(i);
  return std::nullopt;
}

std::string_view to_string(Format f) noexcept {
  const auto i = static_cast<std::size_t>(f);
  return i < std::size(kFormat) ? kFormat[i] : "?";
}

Format detect_format(std::string_view head) {
  if (head.size() >= 4) {
    std::uint32_t m;
    std::memcpy(&m, head.data(), 4);
    if (m == 0xa1b2c3d4 || m == 0xd4c3b2a1 || m == 0xa1b23c4d || m == 0x4d3cb2a1)
      return Format::pcap;
    if (m == 0x0a0d0d0a) return Format::pcapng;
  }
  std::string_view l = first_line(head);
  // a line log may open with "# " comment lines
  for (std::string_view rest = head; l.size() > 1 && l[0] == '#' && l[1] == ' ';) {
    auto nl = rest.find('\n');
    if (nl == std::string_view::npos) break;
    rest.remove_prefix(nl + 1);
    std::string_view next = first_line(rest);
    std::string_view t, d, r;
    if (split_line_log(next, t, d, r) && parse_time(t)) return Format::lines;
    l = next;
  }
  if (is_socat_header(l)) return Format::socat;
  if (l.find("start_time") != std::string_view::npos && l.find(',') != std::string_view::npos)
    return Format::saleae;
  std::string_view t, d, r;
  if (split_line_log(l, t, d, r) && parse_time(t)) return Format::lines;
  return Format::raw;
}

}  // namespace topdump
