#include "output.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>

#include "escape.hpp"
#include "sources.hpp"

namespace topdump {

void Out::flush() {
  if (!buf_.empty()) {
    std::fwrite(buf_.data(), 1, buf_.size(), f_);
    buf_.clear();
  }
  std::fflush(f_);
}

namespace {

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

json note_json(const Note& n) {
  json j;
  j["code"] = to_string(n.code);
  j["severity"] = top::to_string(n.severity);
  j["message"] = ascii_text(n.message);
  return j;
}

json time_json(std::int64_t ts) {
  if (ts == kNoTime) return nullptr;
  return static_cast<double>(ts) / 1e6;
}

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

template <class O>
void put_str(O& o, std::string_view s) {
  if (json_plain(s)) return quoted(o, s);
  o += '"';
  {
    for (char ch : s) {
      auto c = static_cast<unsigned char>(ch);
      if (c == '"' || c == '\\') {
        o += '\\';
        o += ch;
      } else if (c < 0x20) {
        char b[8];
        std::snprintf(b, sizeof b, "\\u%04x", c);
        o += b;
      } else {
        o += ch;
      }
    }
  }
  o += '"';
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

template <class O>
void put_d(O& o, double v) {
  char b[40];
  auto r = std::to_chars(b, b + sizeof b, v);
  o.append(b, static_cast<std::size_t>(r.ptr - b));
}

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

template <class O>
void put_i(O& o, std::int64_t v) {
  char b[24];
  auto r = std::to_chars(b, b + sizeof b, v);
  o.append(b, static_cast<std::size_t>(r.ptr - b));
}

// A double as nlohmann writes it: shortest round-trip digits, ".0" on
// integral values, null for NaN and infinities.
template <class O>
void put_double(O& o, double v) {
  if (!std::isfinite(v)) {
    app(o, "null");
    return;
  }
  char b[40];
  auto r = std::to_chars(b, b + sizeof b, v);
  std::string_view s(b, static_cast<std::size_t>(r.ptr - b));
  o += s;
  if (s.find_first_of(".e") == std::string_view::npos) app(o, ".0");
}

// A string that needs no escaping: the catalog's names, titles, sections,
// units and enum names, finding codes and quirks, header texts (a test
// checks every one of them).
template <class O>
[[gnu::always_inline]] inline void put_plain(O& o, std::string_view s) {
  quoted(o, s);
}

// ,"transport":"udp","from":"...","to":"..."
template <class O>
void put_endpoints(O& o, Transport t, const std::string& from, const std::string& to) {
  app(o, ",\"transport\":\"");
  o += to_string(t);
  app(o, "\",\"from\":");
  put_str(o, from);
  app(o, ",\"to\":");
  put_str(o, to);
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

// A field's value: from its exact decimal (top::exact_decimal checks that the
// double is the one nearest to it) while nlohmann would write it in fixed
// notation, |x| >= 0.001; else the shortest digits of the double.
template <class O>
void put_value(O& o, const top::FieldValue& v) {
  std::int64_t mant = 0;
  int dec = 0;
  if (top::exact_decimal(v, mant, dec) && (mant == 0 || std::fabs(v.value) >= 0.001)) {
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

std::string_view role_text(top::Role r) {
  switch (r) {
    case top::Role::request:
      return "request";
    case top::Role::response:
      return "response";
    case top::Role::any:
      break;
  }
  return "any";
}

template <class O>
void put_finding(O& o, const top::Finding& x) {
  app(o, "{\"code\":\"");
  o += top::to_string(x.code);
  app(o, "\",\"severity\":\"");
  o += top::to_string(x.severity);
  app(o, "\",\"offset\":");
  put_u(o, x.offset);
  app(o, ",\"message\":");
  put_esc(o, x.message);
  if (!x.quirk.empty()) {
    app(o, ",\"quirk\":");
    put_plain(o, x.quirk);
  }
  o += '}';
}

template <class O>
void put_field(O& o, const top::FieldValue& v, const top::Frame& f) {
  const top::FieldSpec& s = *v.spec;
  app(o, "{\"kind\":\"");
  o += top::to_string(s.kind);
  o += '"';
  if (v.none) {
    app(o, ",\"value\":null,\"none\":true");
  } else if (!v.valid) {
    app(o, ",\"value\":null,\"valid\":false");
  } else {
    switch (s.kind) {
      case top::FieldKind::text:
      case top::FieldKind::raw:
        app(o, ",\"value\":");
        put_esc(o, v.text);
        break;
      case top::FieldKind::enum_hex:
      case top::FieldKind::enum_char:
        app(o, ",\"value\":");
        put_i(o, v.integer);
        if (!v.enum_name.empty()) {
          app(o, ",\"name\":");
          put_plain(o, v.enum_name);
        }
        break;
      default:
        app(o, ",\"value\":");
        if (s.scale == 1.0 && s.kind != top::FieldKind::number && s.kind != top::FieldKind::nmea)
          put_i(o, v.integer);
        else
          put_value(o, v);
        if (!v.enum_name.empty()) {
          app(o, ",\"name\":");
          put_plain(o, v.enum_name);
        }
        break;
    }
  }
  if (!s.unit.empty()) {
    app(o, ",\"unit\":");
    put_plain(o, s.unit);
  }
  app(o, ",\"text\":");
  static thread_local std::string text;  // reused: no allocation per field
  text.clear();
  top::append_value(v, text);
  put_esc(o, text);
  app(o, ",\"raw\":");
  put_esc(o, std::string_view(f.raw).substr(v.offset, v.length));
  app(o, ",\"offset\":");
  put_u(o, v.offset);
  o += '}';
}

}  // namespace

// The keys of frame_json() in its order, written directly.
template <class O>
void frame_body(O& o, const top::Frame& f, const top::Decoded& d) {
  app(o, "\"header\":");
  put_plain(o, f.header_text());
  app(o, ",\"src\":");
  put_esc(o, std::string_view(&f.src, 1));
  app(o, ",\"dst\":");
  put_esc(o, std::string_view(&f.dst, 1));
  app(o, ",\"length\":");
  put_u(o, f.data_length);
  app(o, ",\"declared_length\":");
  put_u(o, f.declared_length);
  app(o, ",\"control\":");
  if (f.control)
    put_esc(o, std::string_view(&f.control, 1));
  else
    app(o, "null");
  app(o, ",\"ident\":");
  put_esc(o, f.ident_view());
  app(o, ",\"data\":");
  put_esc(o, f.data());
  app(o, ",\"checksum\":");
  if (f.checksum_present)
    put_esc(o, f.checksum_text());
  else
    app(o, "null");
  app(o, ",\"checksum_ok\":");
  o += std::string_view(f.checksum_ok ? "true" : "false");
  app(o, ",\"expected_checksum\":");
  char hx[2];
  top::put_hex2(f.expected_checksum, hx);
  put_plain(o, std::string_view(hx, 2));
  app(o, ",\"raw\":");
  put_esc(o, f.raw);
  app(o, ",\"dialect\":");
  put_plain(o, top::to_string(d.dialect));
  app(o, ",\"role\":");
  put_plain(o, role_text(d.role));
  app(o, ",\"command\":");
  if (d.command) {
    app(o, "{\"ident\":");
    put_plain(o, d.command->ident);
    app(o, ",\"title\":");
    put_plain(o, d.command->title);
    app(o, ",\"section\":");
    put_plain(o, d.command->section);
    app(o, ",\"address_class\":");
    put_plain(o, std::string_view(&d.command->address, 1));
    o += '}';
  } else {
    app(o, "null");
  }
  app(o, ",\"fields\":");
  o += '{';
  bool first = true;
  for (const auto& v : d.fields) {
    if (!first) o += ',';
    first = false;
    put_plain(o, v.name());
    o += ':';
    put_field(o, v, f);
  }
  app(o, "},\"findings\":");
  o += '[';
  first = true;
  std::string quirks;
  top::Severity w = top::Severity::info;
  auto each = [&](const top::Finding& x) {
    if (!first) o += ',';
    first = false;
    put_finding(o, x);
    if (!x.quirk.empty()) {
      if (!quirks.empty()) quirks += ',';
      put_plain(quirks, x.quirk);
    }
    if (x.severity > w) w = x.severity;
  };
  if (f.findings.size() + d.findings.size() <= 1) {
    for (const auto& x : f.findings) each(x);
    for (const auto& x : d.findings) each(x);
  } else {
    for (const top::Finding* x : all_findings(f, d)) each(*x);
  }
  app(o, "],\"quirks\":");
  o += '[';
  o += quirks;
  app(o, "],\"ok\":");
  o += w != top::Severity::error ? "true" : "false";
}

namespace {

std::string severity_tag(const top::Finding& f) {
  return std::string(top::to_string(f.severity)) + " " + std::string(top::to_string(f.code)) + "@" +
         std::to_string(f.offset) + ": " + f.message +
         (f.quirk.empty() ? "" : " [quirk: " + std::string(f.quirk) + "]");
}

std::string where(std::int64_t ts, Transport t, const std::string* from, const std::string* to) {
  std::string s = format_time(ts);
  if (from) s += " " + std::string(to_string(t)) + " " + *from + " > " + *to;
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------
// JSON

json frame_event_json(const FrameEvent& e) {
  json j;
  j["type"] = "frame";
  j["n"] = e.n;
  j["time"] = time_json(e.ts);
  j["transport"] = to_string(e.transport);
  j["from"] = *e.from;
  j["to"] = *e.to;
  j["conversation"] = e.conv ? e.conv_id() : 0;
  j["record"] = e.pos.record;
  j["index"] = e.pos.index;
  j["offset"] = e.pos.offset;
  j["stream_offset"] = e.stream_offset;
  j.update(frame_json(*e.entry->frame, e.entry->decoded));
  if (e.reply_to)
    j["reply_to"] = e.reply_to;
  else
    j["reply_to"] = nullptr;
  if (e.latency_us >= 0)
    j["latency_ms"] = static_cast<double>(e.latency_us) / 1000.0;
  else
    j["latency_ms"] = nullptr;
  json s = json::array();
  for (const Note& n : e.notes) s.push_back(note_json(n));
  j["session"] = std::move(s);
  return j;
}

void write_frame_json(std::string& out, const FrameEvent& e) {
  W o(out);
  app(o, "{\"type\":\"frame\",\"n\":");
  put_u(o, e.n);
  app(o, ",\"time\":");
  put_time(o, e.ts);
  put_endpoints(o, e.transport, *e.from, *e.to);
  app(o, ",\"conversation\":");
  put_u(o, e.conv ? e.conv_id() : 0);
  app(o, ",\"record\":");
  put_u(o, e.pos.record);
  app(o, ",\"index\":");
  put_u(o, e.pos.index);
  app(o, ",\"offset\":");
  put_u(o, e.pos.offset);
  app(o, ",\"stream_offset\":");
  put_u(o, e.stream_offset);
  o += ',';
  frame_body(o, *e.entry->frame, e.entry->decoded);
  app(o, ",\"reply_to\":");
  if (e.reply_to)
    put_u(o, e.reply_to);
  else
    app(o, "null");
  app(o, ",\"latency_ms\":");
  if (e.latency_us >= 0)
    put_decimal(o, e.latency_us, 3);  // the double nearest to it is latency_us / 1000.0
  else
    app(o, "null");
  app(o, ",\"session\":[");
  bool first = true;
  for (const Note& n : e.notes) {
    if (!first) o += ',';
    first = false;
    app(o, "{\"code\":\"");
    o += to_string(n.code);
    app(o, "\",\"severity\":\"");
    o += top::to_string(n.severity);
    app(o, "\",\"message\":");
    put_text(o, n.message);
    o += '}';
  }
  app(o, "]}\n");
}

json garbage_event_json(const GarbageEvent& e) {
  json j;
  j["type"] = "garbage";
  j["time"] = time_json(e.ts);
  j["transport"] = to_string(e.transport);
  j["from"] = *e.from;
  j["to"] = *e.to;
  j["conversation"] = e.conv ? e.conv_id() : 0;
  j["record"] = e.pos.record;
  j["index"] = e.pos.index;
  j["offset"] = e.pos.offset;
  j.update(garbage_json(*e.item));
  return j;
}

json note_event_json(const NoteEvent& e) {
  json j;
  j["type"] = "finding";
  j["time"] = time_json(e.ts);
  if (e.from) {
    j["transport"] = to_string(e.transport);
    j["from"] = *e.from;
    j["to"] = *e.to;
  } else {
    j["transport"] = nullptr;
    j["from"] = nullptr;
    j["to"] = nullptr;
  }
  j["conversation"] = e.conv ? json(e.conv_id()) : json(nullptr);
  j["record"] = e.pos.record;
  j["offset"] = e.pos.offset;
  j["code"] = to_string(e.note.code);
  j["severity"] = top::to_string(e.note.severity);
  j["message"] = ascii_text(e.note.message);
  if (e.note.frame)
    j["frame"] = e.note.frame;
  else
    j["frame"] = nullptr;
  return j;
}

void JsonSink::frame(const FrameEvent& e) {
  write_frame_json(out_.buf(), e);
  out_.done();
}
void JsonSink::garbage(const GarbageEvent& e) {
  out_.buf() += garbage_event_json(e).dump();
  out_.buf() += '\n';
  out_.done();
}
void write_note_json(std::string& out, const NoteEvent& e) {
  W o(out);
  app(o, "{\"type\":\"finding\",\"time\":");
  put_time(o, e.ts);
  if (e.from) {
    put_endpoints(o, e.transport, *e.from, *e.to);
  } else {
    app(o, ",\"transport\":null,\"from\":null,\"to\":null");
  }
  app(o, ",\"conversation\":");
  if (e.conv)
    put_u(o, e.conv_id());
  else
    app(o, "null");
  app(o, ",\"record\":");
  put_u(o, e.pos.record);
  app(o, ",\"offset\":");
  put_u(o, e.pos.offset);
  app(o, ",\"code\":");
  put_plain(o, to_string(e.note.code));
  app(o, ",\"severity\":");
  put_plain(o, top::to_string(e.note.severity));
  app(o, ",\"message\":");
  put_text(o, e.note.message);
  app(o, ",\"frame\":");
  if (e.note.frame)
    put_u(o, e.note.frame);
  else
    app(o, "null");
  app(o, "}\n");
}

void JsonSink::note(const NoteEvent& e) {
  write_note_json(out_.buf(), e);
  out_.done();
}

// ---------------------------------------------------------------------------
// Text

std::string frame_line(const FrameEvent& e) {
  const top::Frame& f = *e.entry->frame;
  const top::Decoded& d = e.entry->decoded;
  std::string s = "#" + std::to_string(e.n) + " " + where(e.ts, e.transport, e.from, e.to);
  s += " rec " + std::to_string(e.pos.record) + "." + std::to_string(e.pos.index) + "@" +
       std::to_string(e.pos.offset) + " \"" + escape(f.raw) + "\" ";
  s += escape(f.ident_view());
  switch (d.role) {
    case top::Role::request:
      s += " request";
      break;
    case top::Role::response:
      s += " response";
      break;
    case top::Role::any:
      break;
  }
  if (d.command) s += " (" + std::string(d.command->title) + ")";
  std::string sum = d.summary();
  if (!sum.empty()) s += ": " + sum;
  if (e.reply_to) {
    s += " | reply to #" + std::to_string(e.reply_to);
    if (e.latency_us >= 0) {
      char b[48];
      std::snprintf(b, sizeof b, " after %.3f ms", static_cast<double>(e.latency_us) / 1000.0);
      s += b;
    }
  }
  for (const top::Finding* x : all_findings(f, d)) s += " | " + severity_tag(*x);
  for (const Note& n : e.notes)
    s += " | " + std::string(top::to_string(n.severity)) + " " + std::string(to_string(n.code)) +
         ": " + n.message;
  return s;
}

std::string garbage_line(const GarbageEvent& e) {
  const top::StreamItem& g = *e.item;
  return "-- " + where(e.ts, e.transport, e.from, e.to) + " rec " + std::to_string(e.pos.record) +
         "." + std::to_string(e.pos.index) + "@" + std::to_string(e.pos.offset) + " " +
         std::to_string(g.length) + " bytes \"" + escape(g.preview) +
         (g.length > g.preview.size() ? "..." : "") + "\" | " + severity_tag(g.finding);
}

std::string note_line(const NoteEvent& e) {
  std::string s = "!! " + where(e.ts, e.transport, e.from, e.to);
  if (e.pos.record)
    s += " rec " + std::to_string(e.pos.record) + "@" + std::to_string(e.pos.offset);
  s += " " + std::string(top::to_string(e.note.severity)) + " " +
       std::string(to_string(e.note.code)) + ": " + e.note.message;
  return s;
}

void TextSink::frame(const FrameEvent& e) {
  std::string& o = out_.buf();
  o += frame_line(e);
  o += '\n';
  if (verbose_) {
    o += frame_tree(*e.entry->frame, e.entry->decoded);
    for (const Note& n : e.notes)
      o += "  " + std::string(top::to_string(n.severity)) + " " + std::string(to_string(n.code)) +
           ": " + n.message + "\n";
  }
  out_.done();
}
void TextSink::garbage(const GarbageEvent& e) {
  out_.buf() += garbage_line(e) + "\n";
  out_.done();
}
void TextSink::note(const NoteEvent& e) {
  out_.buf() += note_line(e) + "\n";
  out_.done();
}

// ---------------------------------------------------------------------------
// CSV

const std::vector<std::string>& csv_columns() {
  static const std::vector<std::string> c = {
      "n",        "time",     "transport",   "from",     "to",        "conversation", "record",
      "index",    "offset",   "header",      "src",      "dst",       "control",      "ident",
      "data",     "raw",      "checksum_ok", "dialect",  "role",      "title",        "summary",
      "findings", "severity", "ok",          "reply_to", "latency_ms"};
  return c;
}

bool csv_column_ok(const std::string& c) {
  if (c.rfind("field.", 0) == 0 && c.size() > 6) return true;
  const auto& v = csv_columns();
  return std::find(v.begin(), v.end(), c) != v.end();
}

CsvSink::CsvSink(Out& out, std::vector<std::string> columns)
    : out_(out), cols_(std::move(columns)) {
  std::string& o = out_.buf();
  for (std::size_t i = 0; i < cols_.size(); ++i) o += (i ? "," : "") + cols_[i];
  o += '\n';
}

namespace {
void csv_cell(std::string& o, std::string_view v) {
  if (v.find_first_of(",\"\n\r") == std::string_view::npos) {
    o += v;
    return;
  }
  o += '"';
  for (char c : v) {
    if (c == '"') o += '"';
    o += c;
  }
  o += '"';
}
}  // namespace

void CsvSink::frame(const FrameEvent& e) {
  const top::Frame& f = *e.entry->frame;
  const top::Decoded& d = e.entry->decoded;
  std::string& o = out_.buf();
  for (std::size_t i = 0; i < cols_.size(); ++i) {
    if (i) o += ',';
    const std::string& c = cols_[i];
    std::string v;
    if (c == "n")
      v = std::to_string(e.n);
    else if (c == "time")
      v = format_time(e.ts);
    else if (c == "transport")
      v = to_string(e.transport);
    else if (c == "from")
      v = *e.from;
    else if (c == "to")
      v = *e.to;
    else if (c == "conversation")
      v = std::to_string(e.conv_id());
    else if (c == "record")
      v = std::to_string(e.pos.record);
    else if (c == "index")
      v = std::to_string(e.pos.index);
    else if (c == "offset")
      v = std::to_string(e.pos.offset);
    else if (c == "header")
      v = f.header_text();
    else if (c == "src")
      v = escape(std::string_view(&f.src, 1));
    else if (c == "dst")
      v = escape(std::string_view(&f.dst, 1));
    else if (c == "control")
      v = f.control ? escape(std::string_view(&f.control, 1)) : "";
    else if (c == "ident")
      v = escape(f.ident_view());
    else if (c == "data")
      v = escape(f.data());
    else if (c == "raw")
      v = escape(f.raw);
    else if (c == "checksum_ok")
      v = f.checksum_ok ? "true" : "false";
    else if (c == "dialect")
      v = top::to_string(d.dialect);
    else if (c == "role")
      v = d.role == top::Role::request    ? "request"
          : d.role == top::Role::response ? "response"
                                          : "any";
    else if (c == "title")
      v = d.command ? std::string(d.command->title) : "";
    else if (c == "summary")
      v = d.summary();
    else if (c == "findings") {
      for (const top::Finding* x : all_findings(f, d))
        v += (v.empty() ? "" : ";") + std::string(top::to_string(x->code));
      for (const Note& n : e.notes) v += (v.empty() ? "" : ";") + std::string(to_string(n.code));
    } else if (c == "severity")
      v = top::to_string(e.worst());
    else if (c == "ok")
      v = e.worst() == top::Severity::error ? "false" : "true";
    else if (c == "reply_to")
      v = e.reply_to ? std::to_string(e.reply_to) : "";
    else if (c == "latency_ms") {
      if (e.latency_us >= 0) {
        char b[32];
        std::snprintf(b, sizeof b, "%.3f", static_cast<double>(e.latency_us) / 1000.0);
        v = b;
      }
    } else if (c.rfind("field.", 0) == 0) {
      std::string_view name = std::string_view(c).substr(6);
      for (const auto& fv : d.fields)
        if (fv.name() == name) v = format_value(fv);
    }
    csv_cell(o, v);
  }
  o += '\n';
  out_.done();
}

// ---------------------------------------------------------------------------
// Stats

json stats_json(const Stats& s, top::Severity worst) {
  json j;
  j["frames"] = s.frames;
  j["bad_checksum"] = s.bad_checksum;
  j["error_frames"] = s.error_frames;
  j["garbage"] = s.garbage;
  j["records"] = s.records;
  j["records_skipped"] = s.records_skipped;
  j["first_time"] = time_json(s.first);
  j["last_time"] = time_json(s.last);
  j["worst"] = top::to_string(worst);
  json ids = json::object();
  for (const auto& [k, v] : s.per_ident) ids[k] = v;
  j["per_ident"] = std::move(ids);
  json codes = json::object();
  for (const auto& [k, v] : s.per_code) codes[k] = v;
  j["per_finding"] = std::move(codes);
  json p;
  p["requests"] = s.requests;
  p["responses"] = s.responses;
  p["paired"] = s.paired;
  p["unanswered"] = s.unanswered;
  p["unsolicited"] = s.unsolicited;
  j["pairing"] = std::move(p);
  json lat = json::object();
  for (const auto& [k, l] : s.latency) {
    json x;
    x["count"] = l.count();
    x["min_ms"] = static_cast<double>(l.min()) / 1000.0;
    x["median_ms"] = static_cast<double>(l.quantile(0.5)) / 1000.0;
    x["p95_ms"] = static_cast<double>(l.quantile(0.95)) / 1000.0;
    x["max_ms"] = static_cast<double>(l.max()) / 1000.0;
    lat[k] = std::move(x);
  }
  j["latency"] = std::move(lat);
  json convs = json::array();
  for (const ConvStats& c : s.conversations) {
    json x;
    x["id"] = c.id;
    x["transport"] = to_string(c.transport);
    x["a"] = c.a;
    x["b"] = c.b;
    x["dialect"] = top::to_string(c.dialect);
    x["frames"] = c.frames;
    x["requests"] = c.requests;
    x["responses"] = c.responses;
    x["paired"] = c.paired;
    json st = json::array();
    for (const StreamStat& t : c.streams) {
      json y;
      y["ident"] = t.ident;
      y["asked_hz"] = t.asked_hz > 0 ? json(t.asked_hz) : json(nullptr);
      y["measured_hz"] = std::round(t.measured_hz() * 100.0) / 100.0;
      y["frames"] = t.frames;
      st.push_back(std::move(y));
    }
    x["streams"] = std::move(st);
    convs.push_back(std::move(x));
  }
  j["conversations"] = std::move(convs);
  j["conversations_dropped"] = s.conversations_dropped;
  return j;
}

std::string stats_text(const Stats& s, top::Severity worst) {
  std::string o;
  char b[256];
  std::snprintf(
      b, sizeof b,
      "frames %llu (bad checksum %llu, with an error %llu), garbage runs %llu, records %llu "
      "(not TOP %llu), worst finding: %s\n",
      static_cast<unsigned long long>(s.frames), static_cast<unsigned long long>(s.bad_checksum),
      static_cast<unsigned long long>(s.error_frames), static_cast<unsigned long long>(s.garbage),
      static_cast<unsigned long long>(s.records),
      static_cast<unsigned long long>(s.records_skipped),
      std::string(top::to_string(worst)).c_str());
  o += b;
  if (s.first != kNoTime) o += "time " + format_time(s.first) + " .. " + format_time(s.last) + "\n";
  app(o, "per identifier:\n");
  for (const auto& [k, v] : s.per_ident) o += "  " + k + " " + std::to_string(v) + "\n";
  app(o, "per finding:\n");
  for (const auto& [k, v] : s.per_code) o += "  " + k + " " + std::to_string(v) + "\n";
  std::snprintf(
      b, sizeof b,
      "pairing: requests %llu, responses %llu, paired %llu, unanswered %llu, unsolicited %llu\n",
      static_cast<unsigned long long>(s.requests), static_cast<unsigned long long>(s.responses),
      static_cast<unsigned long long>(s.paired), static_cast<unsigned long long>(s.unanswered),
      static_cast<unsigned long long>(s.unsolicited));
  o += b;
  if (!s.latency.empty()) {
    app(o, "latency (ms): ident count min median p95 max\n");
    for (const auto& [k, l] : s.latency) {
      std::snprintf(
          b, sizeof b, "  %s %llu %.3f %.3f %.3f %.3f\n", k.c_str(),
          static_cast<unsigned long long>(l.count()), static_cast<double>(l.min()) / 1000.0,
          static_cast<double>(l.quantile(0.5)) / 1000.0,
          static_cast<double>(l.quantile(0.95)) / 1000.0, static_cast<double>(l.max()) / 1000.0);
      o += b;
    }
  }
  app(o, "conversations:\n");
  for (const ConvStats& c : s.conversations) {
    std::snprintf(
        b, sizeof b,
        "  %llu %s %s <> %s %s: frames %llu, requests %llu, responses %llu, paired %llu\n",
        static_cast<unsigned long long>(c.id), std::string(to_string(c.transport)).c_str(),
        c.a.c_str(), c.b.c_str(), std::string(top::to_string(c.dialect)).c_str(),
        static_cast<unsigned long long>(c.frames), static_cast<unsigned long long>(c.requests),
        static_cast<unsigned long long>(c.responses), static_cast<unsigned long long>(c.paired));
    o += b;
    for (const StreamStat& t : c.streams) {
      std::snprintf(b, sizeof b, "    stream %s: %llu frames at %.2f Hz (asked %s)\n",
                    t.ident.c_str(), static_cast<unsigned long long>(t.frames), t.measured_hz(),
                    t.asked_hz > 0 ? (std::to_string(static_cast<int>(t.asked_hz)) + " Hz").c_str()
                                   : "enable");
      o += b;
    }
  }
  if (s.conversations_dropped)
    o += "  (" + std::to_string(s.conversations_dropped) + " more conversations not listed)\n";
  return o;
}

}  // namespace topdump
