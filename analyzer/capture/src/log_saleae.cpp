// Saleae Logic 2 Async Serial exports: a CSV row per byte.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "log_reader.hpp"
#include "serial_logs.hpp"
#include "top/text.hpp"

namespace topdump {

namespace {

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

}  // namespace

void saleae_log(const std::string& path, std::FILE* file, LineReader& r, CaptureSink& a) {
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

}  // namespace topdump
