// topdump's JSON documents, each key written here once
// (docs/topdump-json.md): the events of read --json (one line each) and the
// frames and garbage of frame --json.
#include "output/json_writer.hpp"
#include "output/output.hpp"
#include "top/motion.hpp"

namespace topdump {

using namespace jsonw;

namespace {

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
    put_text(o, x.quirk);  // evidence may quote its source: escaped
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

// A finding list of one element.
template <class O>
void put_findings(O& o, const top::Finding& x) {
  o += '[';
  put_finding(o, x);
  o += ']';
}

// The keys of a frame, in the order docs/topdump-json.md gives them.
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
  put_or_null(o, f.control != 0, [&] { put_esc(o, std::string_view(&f.control, 1)); });
  app(o, ",\"ident\":");
  put_esc(o, f.ident_view());
  app(o, ",\"data\":");
  put_esc(o, f.data());
  app(o, ",\"checksum\":");
  put_or_null(o, f.checksum_present, [&] { put_esc(o, f.checksum_text()); });
  app(o, ",\"checksum_ok\":");
  put_bool(o, f.checksum_ok);
  app(o, ",\"expected_checksum\":");
  char hx[2];
  top::put_hex2(f.expected_checksum, hx);
  put_plain(o, std::string_view(hx, 2));
  app(o, ",\"raw\":");
  put_esc(o, f.raw);
  app(o, ",\"dialect\":");
  put_plain(o, top::to_string(d.dialect));
  app(o, ",\"role\":");
  put_plain(o, top::to_string(d.role));
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
  static thread_local std::string key;  // reused: no allocation per field
  for (const auto& v : d.fields) {
    if (!first) o += ',';
    first = false;
    key.clear();
    top::append_key(v, key);  // a record's field: "x[1]"
    put_plain(o, key);
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
      put_text(quirks, x.quirk);
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
  put_bool(o, w != top::Severity::error);
}

// The keys of a run of bytes that belong to no frame.
template <class O>
void garbage_body(O& o, const top::StreamItem& g) {
  app(o, "\"garbage\":true,\"length\":");
  put_u(o, g.length);
  app(o, ",\"preview\":");
  put_esc(o, g.preview);
  app(o, ",\"findings\":");
  put_findings(o, g.finding);
  app(o, ",\"ok\":");
  put_bool(o, g.finding.severity != top::Severity::error);
}

// A time in seconds as a JSON number: nlohmann's digits of ts / 1e6 (the
// garbage events only; frame and finding events, the statistics and the
// report write put_time's six decimals).
template <class O>
void put_seconds(O& o, std::int64_t ts) {
  put_or_null(o, ts != kNoTime, [&] { put_double(o, static_cast<double>(ts) / 1e6); });
}

// Where a frame or garbage event is: ,"transport":...,"from":...,"to":...,
// "conversation":N,"record":N,"index":N,"offset":N
template <class O, class Event>
void put_place(O& o, const Event& e) {
  put_endpoints(o, e.transport, *e.from, *e.to);
  app(o, ",\"conversation\":");
  put_u(o, e.conv ? e.conv_id() : 0);
  app(o, ",\"record\":");
  put_u(o, e.pos.record);
  app(o, ",\"index\":");
  put_u(o, e.pos.index);
  app(o, ",\"offset\":");
  put_u(o, e.pos.offset);
}

// {"arg":N,"offset":N, of frame --json
template <class O>
void put_arg(O& o, std::size_t arg, std::size_t offset) {
  app(o, "{\"arg\":");
  put_u(o, arg);
  app(o, ",\"offset\":");
  put_u(o, offset);
  o += ',';
}

}  // namespace

void write_frame_json(std::string& out, const FrameEvent& e) {
  W o(out);
  app(o, "{\"type\":\"frame\",\"n\":");
  put_u(o, e.n);
  app(o, ",\"time\":");
  put_time(o, e.ts);
  put_place(o, e);
  app(o, ",\"stream_offset\":");
  put_u(o, e.stream_offset);
  o += ',';
  frame_body(o, *e.entry->frame, e.entry->decoded);
  app(o, ",\"reply_to\":");
  put_nonzero(o, e.reply_to);
  app(o, ",\"latency_ms\":");
  // the double nearest to it is latency_us / 1000.0
  put_or_null(o, e.latency_us >= 0, [&] { put_decimal(o, e.latency_us, 3); });
  app(o, ",\"copy_of\":");
  put_nonzero(o, e.copy_of);
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

void write_garbage_json(std::string& out, const GarbageEvent& e) {
  W o(out);
  app(o, "{\"type\":\"garbage\",\"time\":");
  put_seconds(o, e.ts);
  put_place(o, e);
  o += ',';
  garbage_body(o, *e.item);
  app(o, "}\n");
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
  put_or_null(o, e.conv != nullptr, [&] { put_u(o, e.conv_id()); });
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
  put_nonzero(o, e.note.frame);
  if (const std::optional<top::Diagnosis> d = diagnosis_of(e.note.code)) {
    // a diagnosis's case (docs/DIAGNOSES.md)
    app(o, ",\"count\":");
    put_u(o, e.note.count);
    app(o, ",\"until\":");
    put_time(o, e.note.until);
    app(o, ",\"ident\":");
    put_or_null(o, e.note.ident[0] != 0, [&] { put_text(o, std::string_view(e.note.ident, 3)); });
    app(o, ",\"axis\":");
    put_or_null(o, e.note.axis >= 0,
                [&] { put_plain(o, top::to_string(static_cast<top::Axis>(e.note.axis))); });
    app(o, ",\"evidence\":");
    put_text(o, top::evidence(*d));
    app(o, ",\"remedy\":");
    put_text(o, top::remedy(*d));
  }
  app(o, "}\n");
}

void write_frame_json(std::string& out, std::size_t arg, std::size_t offset, const top::Frame& f,
                      const top::Decoded& d) {
  W o(out);
  put_arg(o, arg, offset);
  frame_body(o, f, d);
  app(o, "}\n");
}

void write_garbage_json(std::string& out, std::size_t arg, const top::StreamItem& g) {
  W o(out);
  put_arg(o, arg, g.offset);
  garbage_body(o, g);
  app(o, "}\n");
}

void JsonSink::frame(const FrameEvent& e) {
  write_frame_json(out_.buf(), e);
  out_.done(e.ts, e.pos.record);
}
void JsonSink::garbage(const GarbageEvent& e) {
  write_garbage_json(out_.buf(), e);
  out_.done(e.ts, e.pos.record);
}
void JsonSink::note(const NoteEvent& e) {
  write_note_json(out_.buf(), e);
  out_.done(e.ts, e.pos.record);
}

}  // namespace topdump
