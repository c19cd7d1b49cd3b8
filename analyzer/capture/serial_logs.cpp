// Serial sources: logs written by other tools, and a live serial port.
#include <algorithm>
#include <array>
#include <asio.hpp>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <istream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "capture/sources.hpp"
#include "top/text.hpp"

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

namespace {

bool is_socat_header(std::string_view l) {
  // "> 2026/11/22 05:32:42.000581031  length=19 from=0 to=18"
  return l.size() > 24 && (l[0] == '>' || l[0] == '<') && l[1] == ' ' && l[6] == '/' &&
         l[9] == '/' && l.find("length=") != std::string_view::npos;
}

std::string_view first_line(std::string_view s) {
  auto e = s.find('\n');
  std::string_view l = s.substr(0, e);
  if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
  return l;
}

// "<ISO time> <TX|RX> <frame>"
bool split_line_log(std::string_view l, std::string_view& time, std::string_view& dir,
                    std::string_view& rest) {
  auto a = l.find(' ');
  if (a == std::string_view::npos) return false;
  auto b = l.find(' ', a + 1);
  if (b == std::string_view::npos) return false;
  time = l.substr(0, a);
  dir = l.substr(a + 1, b - a - 1);
  rest = l.substr(b + 1);
  return dir == "TX" || dir == "RX";
}

}  // namespace

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

namespace {

Endpoint named(std::string n) {
  Endpoint e;
  e.name = std::move(n);
  return e;
}

// A streambuf over a FILE (an Input's, which may be a pipe).
class FileBuf : public std::streambuf {
 public:
  explicit FileBuf(std::FILE* f) : f_(f) {}

 private:
  int_type underflow() override {
    const std::size_t n = std::fread(buf_.data(), 1, buf_.size(), f_);
    if (n == 0) return traits_type::eof();
    setg(buf_.data(), buf_.data(), buf_.data() + n);
    return traits_type::to_int_type(buf_[0]);
  }
  std::FILE* f_;
  std::array<char, 1 << 16> buf_;  // not zeroed: only what fread wrote is read
};

struct LineReader {
  explicit LineReader(std::FILE* f) : buf(f), in(&buf) {}
  FileBuf buf;
  std::istream in;
  std::string line;
  std::uint64_t number = 0;
  std::uint64_t offset = 0;  // file offset of the current line
  std::uint64_t next = 0;
  bool get() {
    if (!std::getline(in, line)) return false;
    ++number;
    offset = next;
    next += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
};

// "PATH: line N: " and the pieces, in one allocation (a chain of operator+
// made one per piece: a fuzzed log is mostly such notes).
std::string line_note(const std::string& path, std::uint64_t line,
                      std::initializer_list<std::string_view> why) {
  const std::string n = std::to_string(line);
  std::size_t size = path.size() + n.size() + 9;
  for (std::string_view p : why) size += p.size();
  std::string m;
  m.reserve(size);
  m.append(path).append(": line ").append(n).append(": ");
  for (std::string_view p : why) m.append(p);
  return m;
}

// A raw dump holds the bytes one tap received: one direction, named for
// the file, to the end that was not tapped ("peer").
template <class A>
void raw_log(const std::string& path, std::istream& in, A& a) {
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

// socat -v (text) and socat -x -v (hex) dumps. In text mode socat writes
// CR as "\r", LF as a line break and every other non-printable byte as '.',
// so text dumps of binary frames are lossy; -x -v dumps are exact.
template <class A>
void socat_log(const std::string& path, LineReader& r, A& a) {
  Endpoint left = named("left"), right = named("right");
  std::uint64_t chunk_no = 0;
  // Kept from chunk to chunk, so that their storage is reused: a log is
  // mostly headers and short chunks, and these were most of what reading
  // one allocated.
  std::string pending;  // text after the data of a chunk (next header glued on)
  std::string iso;      // the header's time, as ISO 8601
  std::string bytes;    // the chunk's data
  bool have_line = false;
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

// Splits a CSV line into `out`'s first `n` strings (returned), reusing
// their storage: a Saleae export is a row per byte, and a fresh vector of
// strings per row was most of what reading one cost. Stops after `max`
// columns (the rest of the line is not read: a row's columns past the last
// one the header names are never looked at), so n <= max.
std::size_t csv_split(std::string_view l, std::vector<std::string>& out,
                      std::size_t max = SIZE_MAX) {
  std::size_t n = 0;
  auto next = [&]() -> std::string& {
    if (n == out.size()) out.emplace_back();
    std::string& s = out[n++];
    s.clear();
    return s;
  };
  std::string* cur = &next();
  bool q = false;  // inside quotes
  // A run of plain bytes at a time, up to the next byte that matters: the
  // next comma and the next quote are each found with one memchr over the
  // rest of the row, and looked for again only once passed (find_first_of
  // called memchr on its two-byte set for every byte of the row).
  std::size_t comma = l.find(','), quote = l.find('"');
  for (std::size_t i = 0; i < l.size();) {
    if (quote < i) quote = l.find('"', i);
    std::size_t j = quote;
    if (!q) {
      if (comma < i) comma = l.find(',', i);
      j = std::min(comma, quote);
    }
    cur->append(l.substr(i, j - i));
    if (j == std::string_view::npos) break;
    i = j + 1;
    if (q) {
      if (i < l.size() && l[i] == '"')
        *cur += '"', ++i;  // "" inside quotes is a quote
      else
        q = false;
    } else if (l[j] == '"') {
      q = true;
    } else {
      if (n == max) break;
      cur = &next();
    }
  }
  return n;
}

std::optional<int> csv_byte(std::string_view v) {
  if (v.size() == 1) return static_cast<unsigned char>(v[0]);
  if (v.size() >= 3 && v[0] == '0' && (v[1] == 'x' || v[1] == 'X')) {
    int x = 0;
    for (char c : v.substr(2)) {
      const int d = top::hex_value(c);
      if (d < 0) return std::nullopt;
      x = x * 16 + d;
      if (x > 255) return std::nullopt;
    }
    return x;
  }
  if (v.size() >= 2 && v[0] == '\'' && v.back() == '\'') {
    std::string err;
    auto u = top::unescape(v.substr(1, v.size() - 2), err);
    if (u && u->size() == 1) return static_cast<unsigned char>((*u)[0]);
    return std::nullopt;
  }
  int x = 0;
  if (v.empty()) return std::nullopt;
  for (char c : v) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    x = x * 10 + (c - '0');
    if (x > 255) return std::nullopt;
  }
  return x;
}

// Saleae Logic 2 Async Serial export: name,type,start_time,duration,data[,error]
// (times in seconds from the start of the capture; read as seconds after the
// epoch). Each analyzer name is one direction.
const std::string kSerial = "serial", kLine = "line";

template <class A>
void saleae_log(const std::string& path, std::FILE* file, LineReader& r, A& a) {
  if (!r.get()) return;
  std::vector<std::string> head;
  head.resize(csv_split(r.line, head));
  int c_name = -1, c_type = -1, c_time = -1, c_data = -1, c_err = -1;
  for (std::size_t i = 0; i < head.size(); ++i) {
    int* col = head[i] == "name"         ? &c_name
               : head[i] == "type"       ? &c_type
               : head[i] == "start_time" ? &c_time
               : head[i] == "data"       ? &c_data
               : head[i] == "error"      ? &c_err
                                         : nullptr;
    if (!col) continue;
    if (*col >= 0) {
      a.source_note(kNoTime, ACode::log_syntax,
                    line_note(path, 1,
                              {"the header names column \"", top::escape(head[i]),
                               "\" twice; the first one is read"}),
                    1, 0);
      continue;
    }
    *col = static_cast<int>(i);
  }
  if (c_time < 0 || c_data < 0) {
    a.source_note(kNoTime, ACode::log_syntax,
                  line_note(path, 1, {"the header lacks start_time or data"}), 1, 0);
    return;
  }
  // The columns a row is read for: those up to the last one the header names.
  const auto row_columns =
      static_cast<std::size_t>(std::max({c_name, c_type, c_time, c_data, c_err}) + 1);
  // first pass: the first two analyzer names are the two directions
  std::vector<std::string> names;
  {
    // the header line is read: scan from where the reader's FILE stands
    // (it read ahead) after the header, then go back
    const long back = std::ftell(file);
    std::fseek(file, static_cast<long>(r.next), SEEK_SET);
    LineReader scan(file);
    std::string l;
    std::vector<std::string> cols;
    while (names.size() < 2 && std::getline(scan.in, l)) {
      if (!l.empty() && l.back() == '\r') l.pop_back();
      if (c_name < 0 ||
          static_cast<int>(csv_split(l, cols, static_cast<std::size_t>(c_name) + 1)) <= c_name)
        break;
      const std::string& n = cols[static_cast<std::size_t>(c_name)];
      if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    }
    std::fseek(file, back, SEEK_SET);
  }
  std::vector<std::string> cols;  // the row's columns; their storage is reused
  Endpoint from, to;              // the row's ends, reused likewise
  while (r.get()) {
    if (r.line.empty()) continue;
    const int ncols = static_cast<int>(csv_split(r.line, cols, row_columns));
    auto bad = [&](std::initializer_list<std::string_view> why) {
      a.source_note(kNoTime, ACode::log_syntax, line_note(path, r.number, why), r.number, r.offset);
    };
    // every column the header names must be in the row (the header may name
    // a column twice, the later one past the data columns)
    if (ncols <= std::max({c_time, c_data, c_name})) {
      bad({"too few columns"});
      continue;
    }
    if (c_type >= 0 && c_type < ncols && cols[static_cast<std::size_t>(c_type)] != "data") continue;
    const std::string& name = c_name >= 0 ? cols[static_cast<std::size_t>(c_name)] : kSerial;
    auto v = csv_byte(cols[static_cast<std::size_t>(c_data)]);
    if (!v) {
      bad({"data \"", top::escape(cols[static_cast<std::size_t>(c_data)]), "\" is not a byte"});
      continue;
    }
    if (c_err >= 0 && c_err < ncols && !cols[static_cast<std::size_t>(c_err)].empty())
      bad({"the analyzer flagged this byte: ", top::escape(cols[static_cast<std::size_t>(c_err)])});
    char* endp = nullptr;
    const std::string& ts_text = cols[static_cast<std::size_t>(c_time)];
    double secs = std::strtod(ts_text.c_str(), &endp);
    // beyond +-2^62 us (146 000 years) the time is not a time: converting it
    // to an integer would be undefined
    std::int64_t ts =
        (endp && *endp == 0 && !ts_text.empty() && std::isfinite(secs) && std::fabs(secs) < 4.6e12)
            ? static_cast<std::int64_t>(secs * 1e6 + (secs >= 0 ? 0.5 : -0.5))
            : kNoTime;
    const std::string* other = &kLine;
    if (names.size() == 2 && (name == names[0] || name == names[1]))
      other = names[0] == name ? &names[1] : &names[0];
    from.name = name;
    to.name = *other;
    char byte = static_cast<char>(*v);
    a.record(true);
    a.chunk(ts, Transport::serial, from, to, std::string_view(&byte, 1), r.number, 0);
  }
}

template <class A>
void lines_log(const std::string& path, LineReader& r, A& a) {
  Endpoint host = named("host"), device = named("device");
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

}  // namespace

namespace {

template <class A>
bool serial_log(Input& input, Format f, A& a, std::string& error) {
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

// Holds the chunks of one log for merging; source notes go through.
struct Collector {
  struct Chunk {
    std::int64_t ts;
    std::uint64_t record, offset;
    std::string bytes;
  };
  Analyzer& a;
  std::vector<Chunk> chunks;
  std::size_t held = 0;
  bool untimed = false;
  void record(bool) {}
  void source_note(std::int64_t ts, ACode code, std::string message, std::uint64_t record,
                   std::uint64_t offset) {
    a.source_note(ts, code, std::move(message), record, offset);
  }
  void chunk(std::int64_t ts, Transport, const Endpoint&, const Endpoint&, std::string_view bytes,
             std::uint64_t record, std::uint64_t offset) {
    if (ts == kNoTime) untimed = true;
    held += bytes.size() + sizeof(Chunk);
    chunks.push_back(Chunk{ts, record, offset, std::string(bytes)});
  }
};

}  // namespace

bool read_serial_log(Input& input, Format f, Analyzer& a, const SourceOptions&,
                     std::string& error) {
  return serial_log(input, f, a, error);
}

bool read_merged(const std::vector<std::string>& paths, Format format, Analyzer& a,
                 const SourceOptions& o, std::string& error, std::vector<InputInfo>* infos) {
  if (paths.size() != 2) {
    error = "two inputs are merged, not " + std::to_string(paths.size());
    return false;
  }
  std::vector<Collector> logs;
  std::vector<std::string> names;
  std::size_t held = 0;
  for (const std::string& p : paths) {
    Input in;
    if (!open_input(p, in, error)) return false;
    Format f = format;
    if (f == Format::automatic) {
      if (auto why = damaged_capture(in.head)) {
        error = in.name + ": " + *why;
        return false;
      }
      f = detect_format(in.head);
    }
    if (f == Format::pcap || f == Format::pcapng || f == Format::raw) {
      error = in.name + ": a " + std::string(to_string(f)) +
              " input cannot be merged: two inputs are two serial taps, each a log with times "
              "(socat, saleae, lines)";
      return false;
    }
    if (infos) infos->push_back(InputInfo{in.name, f, {}});
    if (o.on_input) o.on_input(InputInfo{in.name, f, {}});
    names.push_back(in.name);
    logs.push_back(Collector{a, {}, 0, false});
    if (!serial_log(in, f, logs.back(), error)) return false;
    held += logs.back().held;
    if (logs.back().untimed) {
      error = in.name + ": a chunk without a time: two taps are merged by time";
      return false;
    }
    if (held > kMaxMergeBytes) {
      error = in.name + ": the two logs hold more than " + std::to_string(kMaxMergeBytes >> 20) +
              " MiB; merge them with fewer bytes";
      return false;
    }
  }
  // each log is one tap, one direction: merged by time, the first log first
  // on equal times
  const Endpoint e0 = named(names[0]), e1 = named(names[1]);
  std::size_t i = 0, j = 0;
  const auto& x = logs[0].chunks;
  const auto& y = logs[1].chunks;
  while (i < x.size() || j < y.size()) {
    const bool first = j == y.size() || (i < x.size() && x[i].ts <= y[j].ts);
    const Collector::Chunk& c = first ? x[i++] : y[j++];
    a.record(true);
    a.chunk(c.ts, Transport::serial, first ? e0 : e1, first ? e1 : e0, c.bytes, c.record, c.offset);
  }
  return true;
}

// ---------------------------------------------------------------------------
// Live serial port

bool read_serial_ports(const std::vector<std::string>& devices, unsigned baud, Analyzer& a,
                       const std::atomic<bool>& stop, std::string& error) {
  asio::io_context io;
  struct Tap {
    asio::serial_port port;
    Endpoint src, dst;
    std::array<char, 4096> buf{};
    std::uint64_t chunk_no = 0, offset = 0;
  };
  std::vector<std::unique_ptr<Tap>> taps;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const std::string& device = devices[i];
    auto t = std::make_unique<Tap>(Tap{asio::serial_port(io), named(device),
                                       named(devices.size() == 2 ? devices[1 - i] : "peer")});
    asio::serial_port& port = t->port;
    asio::error_code ec;
    port.open(device, ec);
    if (ec) {
      error = device + ": " + ec.message();
      return false;
    }
    port.set_option(asio::serial_port_base::baud_rate(baud), ec);
    if (!ec) port.set_option(asio::serial_port_base::character_size(8), ec);
    if (!ec)
      port.set_option(asio::serial_port_base::parity(asio::serial_port_base::parity::none), ec);
    if (!ec)
      port.set_option(asio::serial_port_base::stop_bits(asio::serial_port_base::stop_bits::one),
                      ec);
    if (!ec)
      port.set_option(
          asio::serial_port_base::flow_control(asio::serial_port_base::flow_control::none), ec);
    if (ec) {
      error = device + ": cannot configure " + std::to_string(baud) + " 8N1: " + ec.message();
      return false;
    }
    taps.push_back(std::move(t));
  }
  // A frame is held until the line has been quiet for kSerialQuiet: a CR/LF
  // that follows within it belongs to the frame (an FTDI adapter delivers
  // what it has every 16 ms, its default latency timer).
  using clock = std::chrono::steady_clock;
  clock::time_point last_rx = clock::now();
  bool held = false;  // bytes arrived since the last flush
  asio::steady_timer tick(io);
  bool failed = false;
  std::size_t open = taps.size();
  std::function<void()> arm_tick = [&]() {
    tick.expires_after(std::chrono::milliseconds(10));
    tick.async_wait([&](const asio::error_code& e) {
      if (e) return;
      if (stop.load()) {
        for (auto& t : taps) {
          asio::error_code ignored;
          t->port.cancel(ignored);
        }
        return;
      }
      if (held && clock::now() - last_rx >= kSerialQuiet) {
        a.flush_streams();
        held = false;
      }
      arm_tick();
    });
  };
  std::function<void(Tap&)> arm_read = [&](Tap& t) {
    t.port.async_read_some(asio::buffer(t.buf), [&](const asio::error_code& e, std::size_t n) {
      if (e) {
        if (e != asio::error::operation_aborted && !stop.load()) {
          error = t.src.name + ": " + e.message();
          failed = true;
          for (auto& u : taps) {
            asio::error_code ignored;
            u->port.cancel(ignored);
          }
        }
        if (--open == 0) tick.cancel();
        return;
      }
      ++t.chunk_no;
      last_rx = clock::now();
      held = true;
      a.record(true);
      a.chunk(now_us(), Transport::serial, t.src, t.dst, std::string_view(t.buf.data(), n),
              t.chunk_no, t.offset);
      t.offset += n;
      arm_read(t);
    });
  };
  for (auto& t : taps) arm_read(*t);
  arm_tick();
  io.run();
  return !failed;
}

}  // namespace topdump
