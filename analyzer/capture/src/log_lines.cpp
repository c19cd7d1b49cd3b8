// Line logs: "<ISO-8601 time> <TX|RX> <frame>", the frame's bytes escaped.
#include "capture/time.hpp"
#include "log_reader.hpp"
#include "serial_logs.hpp"
#include "top/text.hpp"

namespace topdump {

void lines_log(const std::string& path, LineReader& r, CaptureSink& a) {
  Endpoint host = named("host"), device = named("device");
  // Every line names its direction: the log records both, and a device
  // with no RX line was silent, not untapped (an outside capture's
  // TX-only log named nothing where its socat twin named silent-device).
  a.both_ways();
  while (r.get()) {
    if (r.line.empty() || (r.line.size() > 1 && r.line[0] == '#' && r.line[1] == ' ')) continue;
    std::string_view t, d, rest;
    auto bad = [&](std::initializer_list<std::string_view> why) {
      a.source_note(kNoTime, ACode::log_syntax, line_note(path, r.number, why), r.number, r.offset);
    };
    if (!split_line_log(r.line, t, d, rest)) {
      bad({"expected \"<ISO-8601 time> <TX|RX> <frame>\""});
      continue;
    }
    auto ts = parse_time(t);
    if (!ts) {
      bad({"bad time \"", top::escape(t), "\""});
      continue;
    }
    std::string err;
    auto bytes = top::unescape(rest, err);
    if (!bytes) {
      bad({err});
      continue;
    }
    a.record(true);
    bool tx = d == "TX";
    a.chunk(*ts, Transport::serial, tx ? host : device, tx ? device : host, *bytes, r.number,
            static_cast<std::uint64_t>(rest.data() - r.line.data()));
  }
}

}  // namespace topdump
