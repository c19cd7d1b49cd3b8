// socat -v and socat -x -v dumps: a header line per chunk, then its bytes
// as text or hex.
#include <algorithm>
#include <charconv>
#include <cstdint>

#include "capture/time.hpp"
#include "log_reader.hpp"
#include "serial_logs.hpp"
#include "top/detail/text.hpp"

namespace topdump {

// socat -v (text) and socat -x -v (hex) dumps. In text mode socat writes
// CR as "\r", LF as a line break and every other non-printable byte as '.',
// so text dumps of binary frames are lossy; -x -v dumps are exact.
void socat_log(const std::string& path, LineReader& r, CaptureSink& a) {
  Endpoint left = named("left"), right = named("right");
  std::uint64_t chunk_no = 0;
  // Kept from chunk to chunk, so that their storage is reused: a log is
  // mostly headers and short chunks, and these were most of what reading
  // one allocated.
  std::string pending;  // text after the data of a chunk (next header glued on)
  std::string iso;      // the header's time, as ISO 8601
  std::string bytes;    // the chunk's data
  bool have_line = false;
  a.both_ways();  // socat relays and logs both directions
  for (;;) {
    if (!have_line) {
      if (!r.get()) break;
    }
    have_line = false;
    std::string_view l = r.line;
    if (!pending.empty()) {
      pending += r.line;
      l = pending;
    }
    if (l.empty() || l == "--") {
      pending.clear();
      continue;
    }
    if (!is_socat_header(l)) {
      a.source_note(kNoTime, ACode::log_syntax,
                    line_note(path, r.number,
                              {"expected a socat chunk header (\"> YYYY/MM/DD ... length=N\")"}),
                    r.number, r.offset);
      pending.clear();
      continue;
    }
    ++chunk_no;
    a.record(true);
    bool rtl = l[0] == '<';
    // time: "YYYY/MM/DD HH:MM:SS.nnnnnnnnn" (local time of the logging host; read as UTC)
    iso.assign(l.substr(2, 29));
    if (iso.size() >= 10) iso[4] = iso[7] = '-', iso[10] = 'T';
    auto sp = iso.find(' ');
    if (sp != std::string::npos) iso.resize(sp);
    auto ts = parse_time(iso);
    std::int64_t t = ts ? *ts : kNoTime;
    // "length=N": the decimal digits after it. Anything else is noted and
    // read as 0 (a "length=-5" was once read as 2^64 - 5 and took the rest
    // of the log for this chunk's data); too many digits read as the most.
    const std::string_view len_text = l.substr(l.find("length=") + 7);
    std::size_t length = 0;
    const std::errc len_error =
        std::from_chars(len_text.data(), len_text.data() + len_text.size(), length).ec;
    if (len_error == std::errc::result_out_of_range) length = SIZE_MAX;
    if (len_error == std::errc::invalid_argument)
      a.source_note(t, ACode::log_syntax,
                    line_note(path, r.number, {"the chunk header's length is not a number"}),
                    r.number, r.offset);
    pending.clear();
    bytes.clear();
    bool hex = false, decided = false;
    while (bytes.size() < length && r.get()) {
      std::string_view d = r.line;
      if (!decided) {
        decided = true;
        hex = d.size() >= 3 && d[0] == ' ' && top::hex_value(d[1]) >= 0 &&
              top::hex_value(d[2]) >= 0 && (d.size() == 3 || d[3] == ' ');
      }
      if (hex) {
        std::string_view h = d.substr(0, std::min<std::size_t>(d.size(), 49));
        for (std::size_t i = 1; i + 1 < h.size() && bytes.size() < length; i += 3) {
          const int hi = top::hex_value(h[i]), lo = top::hex_value(h[i + 1]);
          if (hi < 0 || lo < 0) break;
          bytes.push_back(static_cast<char>(hi << 4 | lo));
        }
        continue;
      }
      // text: "\r" is CR, the line break is LF
      for (std::size_t i = 0; i < d.size() && bytes.size() < length; ++i) {
        if (d[i] == '\\' && i + 1 < d.size() && d[i + 1] == 'r') {
          bytes.push_back('\r');
          ++i;
        } else {
          bytes.push_back(d[i]);
        }
        if (bytes.size() == length && i + 1 < d.size()) {
          // the next header follows the data on the same line
          pending.assign(d.substr(i + 1));
        }
      }
      if (bytes.size() < length) bytes.push_back('\n');
    }
    if (!hex && !pending.empty()) {
      r.line.swap(pending);
      pending.clear();
      have_line = true;
    }
    if (bytes.size() < length)
      a.source_note(t, ACode::log_syntax,
                    top::cat({path, ": chunk ", std::to_string(chunk_no), " (line ",
                              std::to_string(r.number), "): ", std::to_string(bytes.size()), " of ",
                              std::to_string(length), " bytes present"}),
                    chunk_no, bytes.size());
    a.chunk(t, Transport::serial, rtl ? right : left, rtl ? left : right, bytes, chunk_no, 0);
  }
}

}  // namespace topdump
