// The one JSON writer of topdump: appends to a std::string (or the inline
// appender W of the per-frame path) exactly what nlohmann's dump() would
// write for the same values, without building a document. Every output
// (read --json, stats --json, frame --json) writes through these; the tests
// parse the result with nlohmann and compare it with a reference built
// there. Keys are written where each document is written (json_events.cpp,
// stats_out.cpp, report/json.cpp), once; what two documents share is
// written here: a time (put_time), a latency summary (latency_members), a
// conversation's names (conversation_members), an object of counts
// (counts_member) and a push stream (stream_members).
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "output/escape.hpp"
#include "session/analyzer.hpp"
#include "top/detail/decimal.hpp"
#include "top/detail/text.hpp"
#include "top/top.hpp"

namespace topdump::jsonw {

// An append-only writer over a std::string with inline appends (the
// library's std::string::append is an out-of-line call; this path runs a
// hundred appends per frame).
class W {
 public:
  explicit W(std::string& s) : s_(s), base_(s.size()) {
    s_.resize(base_ + 2048);
    p_ = s_.data() + base_;
    end_ = s_.data() + s_.size();
  }
  ~W() { s_.resize(static_cast<std::size_t>(p_ - s_.data())); }
  W(const W&) = delete;
  W& operator=(const W&) = delete;
  [[gnu::always_inline]] void append(const char* d, std::size_t n) {
    if (static_cast<std::size_t>(end_ - p_) < n) grow(n);
    copy(p_, d, n);
    p_ += n;
  }
  // memcpy for the short strings of a frame line (names, digits, data)
  // without a call: two overlapping fixed-size moves, reading only [d, d+n).
  [[gnu::always_inline]] static void copy(char* p, const char* d, std::size_t n) {
    if (n >= 8 && n <= 16) {
      std::uint64_t a, b;
      std::memcpy(&a, d, 8);
      std::memcpy(&b, d + n - 8, 8);
      std::memcpy(p, &a, 8);
      std::memcpy(p + n - 8, &b, 8);
    } else if (n >= 4 && n < 8) {
      std::uint32_t a, b;
      std::memcpy(&a, d, 4);
      std::memcpy(&b, d + n - 4, 4);
      std::memcpy(p, &a, 4);
      std::memcpy(p + n - 4, &b, 4);
    } else if (n < 4) {
      for (std::size_t i = 0; i < n; ++i) p[i] = d[i];
    } else {
      std::memcpy(p, d, n);
    }
  }
  [[gnu::always_inline]] W& operator+=(char c) {
    if (p_ == end_) grow(1);
    *p_++ = c;
    return *this;
  }
  W& operator+=(std::string_view v) {
    append(v.data(), v.size());
    return *this;
  }
  // '"' + v + '"' (v needs no escaping)
  [[gnu::always_inline]] void quoted(std::string_view v) {
    if (static_cast<std::size_t>(end_ - p_) < v.size() + 2) grow(v.size() + 2);
    *p_++ = '"';
    copy(p_, v.data(), v.size());
    p_ += v.size();
    *p_++ = '"';
  }

 private:
  void grow(std::size_t n) {
    auto used = static_cast<std::size_t>(p_ - s_.data());
    s_.resize(std::max(s_.size() * 2, used + n + 2048));
    p_ = s_.data() + used;
    end_ = s_.data() + s_.size();
  }
  std::string& s_;
  std::size_t base_;
  char* p_;
  char* end_;
};

template <class O, std::size_t N>
[[gnu::always_inline]] inline void app(O& o, const char (&lit)[N]) {
  o.append(lit, N - 1);
}

// '"' + s + '"' through the writer's one-check path, or appends.
template <class O>
[[gnu::always_inline]] inline void quoted(O& o, std::string_view s) {
  if constexpr (requires { o.quoted(s); }) {
    o.quoted(s);
  } else {
    o += '"';
    o += s;
    o += '"';
  }
}

// A JSON string as nlohmann writes it (the output is ASCII: every string
// the tools write is escaped or ASCII by construction): '"' and '\\'
// escaped, \b \t \n \f \r short, other bytes below 0x20 as \u00xx.
template <class O>
void put_str(O& o, std::string_view s) {
  if (json_plain(s)) return quoted(o, s);
  o += '"';
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      o += '\\';
      o += ch;
    } else if (c >= 0x20) {
      o += ch;
    } else {
      static constexpr char kShort[] = "btnvfr";  // 0x08-0x0D; \v has no JSON escape
      static constexpr char kHex[] = "0123456789abcdef";
      if (c >= 0x08 && c <= 0x0D && c != 0x0B) {
        const char e[2] = {'\\', kShort[c - 0x08]};
        o.append(e, 2);
      } else {
        const char e[6] = {'\\', 'u', '0', '0', kHex[c >> 4], kHex[c & 15]};
        o.append(e, 6);
      }
    }
  }
  o += '"';
}

// put() where there is a value (`has`), else null.
template <class O, class Put>
[[gnu::always_inline]] inline void put_or_null(O& o, bool has, Put put) {
  if (has)
    put();
  else
    app(o, "null");
}

template <class O>
[[gnu::always_inline]] inline void put_bool(O& o, bool v) {
  o += std::string_view(v ? "true" : "false");
}

template <class O>
void put_u(O& o, std::uint64_t v) {
  if (v < 100) {  // most of a line's numbers: indexes, offsets, lengths, ids
    char b[2] = {static_cast<char>('0' + v / 10), static_cast<char>('0' + v % 10)};
    o.append(v < 10 ? b + 1 : b, v < 10 ? 1 : 2);
    return;
  }
  char b[24];
  auto r = std::to_chars(b, b + sizeof b, v);
  o.append(b, static_cast<std::size_t>(r.ptr - b));
}

// The one encoding of a time in topdump's JSON documents (read --json's
// frame and finding events, stats --json, report --json): seconds since the
// epoch with six decimals, exactly the microseconds ("1714564800.004000");
// null for none.
template <class O>
void put_time(O& o, std::int64_t ts) {
  if (ts == kNoTime) {
    app(o, "null");
    return;
  }
  // before 1970 (a log's negative seconds): the sign, then the magnitude
  std::uint64_t mag = ts < 0 ? 0 - static_cast<std::uint64_t>(ts) : static_cast<std::uint64_t>(ts);
  if (ts < 0) o += '-';
  std::uint64_t sec = mag / 1000000, frac = mag % 1000000;
  put_u(o, sec);
  char b[7];
  b[0] = '.';
  for (int i = 6; i >= 1; --i) {
    b[i] = static_cast<char>('0' + frac % 10);
    frac /= 10;
  }
  o.append(b, 7);
}

// A frame number or a count that is 0 for none: null then.
template <class O>
void put_nonzero(O& o, std::uint64_t v) {
  put_or_null(o, v != 0, [&] { put_u(o, v); });
}

template <class O>
void put_i(O& o, std::int64_t v) {
  char b[24];
  auto r = std::to_chars(b, b + sizeof b, v);
  o.append(b, static_cast<std::size_t>(r.ptr - b));
}

// A double laid out as nlohmann lays it out: fixed notation while the point
// falls within 15 digits left of the digits and 4 zeros right ("12.5",
// "100.0", "0.0001"), else d.ddde+XX with at least two exponent digits;
// "-0.0" and "0.0" for zeros, null for NaN and infinities. The digits are the
// shortest that read back as the same double (std::to_chars). nlohmann's
// Grisu2 gives the same digits for the times, latencies and rates topdump
// writes from the bundled captures and the benchmark's (compared byte by
// byte in tests), and for some other doubles one or two digits more: the
// number read back is the same either way.
template <class O>
void put_double(O& o, double v) {
  if (!std::isfinite(v)) {
    app(o, "null");
    return;
  }
  char b[64];
  char* p = b;
  if (std::signbit(v)) {
    *p++ = '-';
    v = -v;
  }
  if (v == 0) {
    *p++ = '0';
    *p++ = '.';
    *p++ = '0';
    o.append(b, static_cast<std::size_t>(p - b));
    return;
  }
  char sci[40];  // "d.ddde+XX", the shortest digits
  const auto r = std::to_chars(sci, sci + sizeof sci, v, std::chars_format::scientific);
  char digits[20];
  int k = 0;
  const char* q = sci;
  for (; *q != 'e' && q < r.ptr; ++q)
    if (*q != '.') digits[k++] = *q;
  int e10 = 0;
  std::from_chars(q + 1 + (q[1] == '+'), r.ptr, e10);
  const int n = e10 + 1;  // the value is 0.digits * 10^n
  if (k <= n && n <= 15) {
    p = std::copy(digits, digits + k, p);
    p = std::fill_n(p, n - k, '0');
    *p++ = '.';
    *p++ = '0';
  } else if (0 < n && n <= 15) {
    p = std::copy(digits, digits + n, p);
    *p++ = '.';
    p = std::copy(digits + n, digits + k, p);
  } else if (-4 < n && n <= 0) {
    *p++ = '0';
    *p++ = '.';
    p = std::fill_n(p, -n, '0');
    p = std::copy(digits, digits + k, p);
  } else {
    *p++ = digits[0];
    if (k > 1) {
      *p++ = '.';
      p = std::copy(digits + 1, digits + k, p);
    }
    *p++ = 'e';
    int x = n - 1;
    *p++ = x < 0 ? '-' : '+';
    if (x < 0) x = -x;
    if (x >= 100) *p++ = static_cast<char>('0' + x / 100);
    *p++ = static_cast<char>('0' + x / 10 % 10);
    *p++ = static_cast<char>('0' + x % 10);
  }
  o.append(b, static_cast<std::size_t>(p - b));
}

// A string that needs no escaping: the catalog's names, titles, sections,
// units and enum names, finding codes, header texts (a test checks every
// one of them). Not a quirk: it is a source's evidence, which may quote it
// (put_text).
template <class O>
[[gnu::always_inline]] inline void put_plain(O& o, std::string_view s) {
  quoted(o, s);
}

// A message (ASCII by convention) as a JSON string: put_str(ascii_text(s)).
template <class O>
void put_text(O& o, std::string_view s) {
  for (unsigned char c : s)
    if (c >= 0x80) return put_str(o, std::string_view(ascii_text(s)));
  put_str(o, s);
}

// mantissa / 10^decimals as JSON: fixed notation, trailing zeros dropped
// but one digit kept after the point ("5.0", "-2.95"), which is how nlohmann
// writes the double nearest to it while 0.001 <= |x| < 10^15.
template <class O>
void put_decimal(O& o, std::int64_t mantissa, int decimals) {
  char b[40];
  char* e = b + sizeof b;
  char* p = e;
  std::uint64_t u = mantissa < 0 ? 0 - static_cast<std::uint64_t>(mantissa)
                                 : static_cast<std::uint64_t>(mantissa);
  bool any = false;  // a nonzero fraction digit written
  for (int i = 0; i < decimals; ++i) {
    const auto digit = static_cast<char>('0' + u % 10);
    u /= 10;
    if (any || digit != '0') {
      *--p = digit;
      any = true;
    }
  }
  if (!any) *--p = '0';
  *--p = '.';
  do {
    *--p = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u);
  if (mantissa < 0) *--p = '-';
  o.append(p, static_cast<std::size_t>(e - p));
}

// A field's value: from its exact decimal (top::detail::exact_decimal checks that the
// double is the one nearest to it) while nlohmann would write it in fixed
// notation, |x| >= 0.001; else the shortest digits of the double.
template <class O>
void put_value(O& o, const top::FieldValue& v) {
  std::int64_t mant = 0;
  int dec = 0;
  if (top::detail::exact_decimal(v, mant, dec) && (mant == 0 || std::fabs(v.value) >= 0.001)) {
    put_decimal(o, mant, dec);
    return;
  }
  put_double(o, v.value);
}

// put_str(escape(bytes)) without the temporary when nothing needs escaping.
template <class O>
void put_esc(O& o, std::string_view bytes) {
  if (json_plain(bytes)) {
    quoted(o, bytes);
  } else {
    put_str(o, std::string_view(escape(bytes)));
  }
}

// Objects and arrays laid out as nlohmann's dump(indent) lays them out:
// compact with indent < 0 ({"a":1,"b":[]}), else one member per line,
// "key": value, and {} / [] when empty. Values are written with the put_*
// functions into out() between key() (or item()) and the next call.
class Doc {
 public:
  Doc(std::string& out, int indent) : o_(out), indent_(indent) {}
  std::string& out() { return o_; }
  void open_object() { open('{'); }
  void close_object() { close('}'); }
  void open_array() { open('['); }
  void close_array() { close(']'); }
  // Starts a member of the open object.
  void key(std::string_view k) {
    item();
    put_str(o_, k);
    if (indent_ >= 0)
      app(o_, ": ");
    else
      o_ += ':';
  }
  // A member that is an object or an array, opened; an element of the open
  // array that is an object, opened.
  void key_object(std::string_view k) {
    key(k);
    open_object();
  }
  void key_array(std::string_view k) {
    key(k);
    open_array();
  }
  void item_object() {
    item();
    open_object();
  }
  // A member `k` that is an array of one object per element of `r`, whose
  // members `each(x)` writes.
  template <class Range, class Each>
  void key_objects(std::string_view k, const Range& r, Each&& each) {
    key_array(k);
    for (const auto& x : r) {
      item_object();
      each(x);
      close_object();
    }
    close_array();
  }
  // A member and its value: a count, a string, a time (put_time).
  void u(std::string_view k, std::uint64_t v) {
    key(k);
    put_u(o_, v);
  }
  void str(std::string_view k, std::string_view v) {
    key(k);
    put_str(o_, v);
  }
  void time(std::string_view k, std::int64_t v) {
    key(k);
    put_time(o_, v);
  }
  // Starts an element of the open array.
  void item() {
    if (!first_.back()) o_ += ',';
    first_.back() = false;
    newline();
  }

 private:
  void open(char c) {
    o_ += c;
    first_.push_back(true);
  }
  void close(char c) {
    const bool empty = first_.back();
    first_.pop_back();
    if (!empty) newline();
    o_ += c;
  }
  void newline() {
    if (indent_ < 0) return;
    o_ += '\n';
    o_.append(first_.size() * static_cast<std::size_t>(indent_), ' ');
  }
  std::string& o_;
  int indent_;
  std::vector<bool> first_;
};

// The members of one identifier's latency summary, in the open object of
// `j`: count, min_ms, p50_ms, p90_ms, p95_ms, p99_ms, max_ms (milliseconds,
// the microseconds / 1000). stats --json writes these; report --json
// appends its histogram after them.
void latency_members(Doc& j, const Latency& l);

// The members that name a conversation, in the open object of `j`: id,
// transport, a, b. stats --json then writes its dialect and counts; report
// --json its dialect, model and frames.
void conversation_members(Doc& j, const ConvStats& c);

// A member `k` that is an object of counts by name (per identifier, per
// finding code, per sender).
void counts_member(Doc& j, std::string_view k, const std::map<std::string, std::uint64_t>& m);

// How a document writes a push stream: stats --json without the request
// that asked for it and with the measured rate to 0.01 Hz; report --json
// with both, the rate to 0.0001 Hz.
struct StreamKeys {
  bool asked_by = false;
  double measured_per_hz = 100;  // the measured rate is rounded to 1/this Hz
};
// The members of one push stream, in the open object of `j`: ident,
// asked_by (when `k` says), asked_hz (null: no rate asked), measured_hz,
// periodic, frames. stats --json writes these; report --json appends its
// rate plot and gaps after them.
void stream_members(Doc& j, const StreamStat& t, StreamKeys k);

}  // namespace topdump::jsonw
