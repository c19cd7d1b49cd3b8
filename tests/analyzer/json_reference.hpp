// The reference of topdump's JSON, built with nlohmann: the tests parse
// what the one writer (analyzer/output/include/output/json_writer.hpp) writes and compare it
// with these, value by value and, where nlohmann's dump() is the format
// (garbage events, frame --json, stats --json), byte by byte.
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "capture/sources.hpp"
#include "output/escape.hpp"
#include "output/output.hpp"
#include "top/detail/text.hpp"
#include "top/motion.hpp"

namespace topdump::reference {

using json = nlohmann::ordered_json;

inline std::string hex2(std::uint8_t v) {
  char b[3];
  top::put_hex2(v, b);
  b[2] = 0;
  return b;
}

inline json field_json(const top::FieldValue& v, const top::Frame& f) {
  json j;
  const top::FieldSpec& s = *v.spec;
  j["kind"] = top::to_string(s.kind);
  if (v.none) {
    j["value"] = nullptr;
    j["none"] = true;
  } else if (!v.valid) {
    j["value"] = nullptr;
    j["valid"] = false;
  } else {
    switch (s.kind) {
      case top::FieldKind::text:
      case top::FieldKind::raw:
        j["value"] = escape(v.text);
        break;
      case top::FieldKind::enum_hex:
      case top::FieldKind::enum_char:
        j["value"] = v.integer;
        if (!v.enum_name.empty()) j["name"] = v.enum_name;
        break;
      default:
        if (s.scale == 1.0 && s.kind != top::FieldKind::number && s.kind != top::FieldKind::nmea)
          j["value"] = v.integer;
        else
          j["value"] = v.value;
        if (!v.enum_name.empty()) j["name"] = v.enum_name;
        break;
    }
  }
  if (!s.unit.empty()) j["unit"] = s.unit;
  j["text"] = escape(format_value(v));
  j["raw"] = escape(std::string_view(f.raw).substr(v.offset, v.length));
  j["offset"] = v.offset;
  return j;
}

inline json finding_json(const top::Finding& x) {
  json j;
  j["code"] = top::to_string(x.code);
  j["severity"] = top::to_string(x.severity);
  j["offset"] = x.offset;
  j["message"] = escape(x.message);
  if (!x.quirk.empty()) j["quirk"] = x.quirk;
  return j;
}

inline json frame_json(const top::Frame& f, const top::Decoded& d) {
  json j;
  j["header"] = f.header_text();
  j["src"] = escape(std::string_view(&f.src, 1));
  j["dst"] = escape(std::string_view(&f.dst, 1));
  j["length"] = f.data_length;
  j["declared_length"] = f.declared_length;
  if (f.control)
    j["control"] = escape(std::string_view(&f.control, 1));
  else
    j["control"] = nullptr;
  j["ident"] = escape(f.ident_view());
  j["data"] = escape(f.data());
  if (f.checksum_present)
    j["checksum"] = escape(f.checksum_text());
  else
    j["checksum"] = nullptr;
  j["checksum_ok"] = f.checksum_ok;
  j["expected_checksum"] = hex2(f.expected_checksum);
  j["raw"] = escape(f.raw);
  j["dialect"] = top::to_string(d.dialect);
  j["role"] = top::to_string(d.role);
  if (d.command) {
    json c;
    c["ident"] = d.command->ident;
    c["title"] = d.command->title;
    c["section"] = d.command->section;
    c["address_class"] = std::string(1, d.command->address);
    j["command"] = std::move(c);
  } else {
    j["command"] = nullptr;
  }
  json fields = json::object();
  for (const auto& v : d.fields) fields[top::field_key(v)] = field_json(v, f);
  j["fields"] = std::move(fields);
  json findings = json::array();
  json quirks = json::array();
  for (const top::Finding* x : all_findings(f, d)) {
    findings.push_back(finding_json(*x));
    if (!x->quirk.empty()) quirks.push_back(x->quirk);
  }
  j["findings"] = std::move(findings);
  j["quirks"] = std::move(quirks);
  j["ok"] = worst(f, d) != top::Severity::error;
  return j;
}

inline json garbage_json(const top::StreamItem& g) {
  json j;
  j["garbage"] = true;
  j["length"] = g.length;
  j["preview"] = escape(g.preview);
  j["findings"] = json::array({finding_json(g.finding)});
  j["ok"] = g.finding.severity != top::Severity::error;
  return j;
}

inline json note_json(const Note& n) {
  json j;
  j["code"] = to_string(n.code);
  j["severity"] = top::to_string(n.severity);
  j["message"] = ascii_text(n.message);
  return j;
}

inline json time_json(std::int64_t ts) {
  if (ts == kNoTime) return nullptr;
  return static_cast<double>(ts) / 1e6;
}

// A time as the documents write it, six decimals (docs/topdump-json.md),
// which nlohmann cannot write: a string "@T<seconds>.<micros>" that dump()
// below turns into that number.
inline json time_exact(std::int64_t ts) {
  if (ts == kNoTime) return nullptr;
  const std::uint64_t mag =
      ts < 0 ? 0 - static_cast<std::uint64_t>(ts) : static_cast<std::uint64_t>(ts);
  char b[48];
  std::snprintf(b, sizeof b, "@T%s%llu.%06llu", ts < 0 ? "-" : "",
                static_cast<unsigned long long>(mag / 1000000),
                static_cast<unsigned long long>(mag % 1000000));
  return std::string(b);
}

// j.dump(indent) with each time_exact() string written as its number.
inline std::string dump(const json& j, int indent = -1) {
  std::string s = j.dump(indent);
  for (std::size_t at; (at = s.find("\"@T")) != std::string::npos;) {
    const std::size_t end = s.find('"', at + 1);
    s = s.substr(0, at) + s.substr(at + 3, end - at - 3) + s.substr(end + 1);
  }
  return s;
}

template <class Event>
void place_json(json& j, const Event& e) {
  j["transport"] = to_string(e.transport);
  j["from"] = *e.from;
  j["to"] = *e.to;
  j["conversation"] = e.conv ? e.conv_id() : 0;
  j["record"] = e.pos.record;
  j["index"] = e.pos.index;
  j["offset"] = e.pos.offset;
}

inline json frame_event_json(const FrameEvent& e) {
  json j;
  j["type"] = "frame";
  j["n"] = e.n;
  j["time"] = time_json(e.ts);
  place_json(j, e);
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
  if (e.copy_of)
    j["copy_of"] = e.copy_of;
  else
    j["copy_of"] = nullptr;
  json s = json::array();
  for (const Note& n : e.notes) s.push_back(note_json(n));
  j["session"] = std::move(s);
  return j;
}

inline json garbage_event_json(const GarbageEvent& e) {
  json j;
  j["type"] = "garbage";
  j["time"] = time_json(e.ts);
  place_json(j, e);
  j.update(garbage_json(*e.item));
  return j;
}

inline json note_event_json(const NoteEvent& e) {
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
  if (const std::optional<top::Diagnosis> d = diagnosis_of(e.note.code)) {
    // a diagnosis's case (docs/topdump-json.md "Diagnoses")
    j["count"] = e.note.count;
    j["until"] = time_json(e.note.until);
    j["ident"] =
        e.note.ident[0] ? json(ascii_text(std::string_view(e.note.ident, 3))) : json(nullptr);
    j["axis"] = e.note.axis >= 0
                    ? json(std::string(top::to_string(static_cast<top::Axis>(e.note.axis))))
                    : json(nullptr);
    j["evidence"] = std::string(top::evidence(*d));
    j["remedy"] = std::string(top::remedy(*d));
  }
  return j;
}

inline json stats_json(const Stats& s, top::Severity worst) {
  json j;
  j["frames"] = s.frames;
  j["bad_checksum"] = s.bad_checksum;
  j["error_frames"] = s.error_frames;
  j["garbage"] = s.garbage;
  j["records"] = s.records;
  j["records_skipped"] = s.records_skipped;
  j["first_time"] = time_exact(s.first);
  j["last_time"] = time_exact(s.last);
  j["worst"] = top::to_string(worst);
  j["per_ident"] = s.per_ident;  // std::map: an object, {} when empty
  j["per_finding"] = s.per_code;
  j["pairing"] = {{"requests", s.requests},       {"responses", s.responses},
                  {"paired", s.paired},           {"unanswered", s.unanswered},
                  {"unsolicited", s.unsolicited}, {"copies", s.copies}};
  json lat = json::object();
  for (const auto& [k, l] : s.latency) {
    json x;
    x["count"] = l.count();
    x["min_ms"] = static_cast<double>(l.min()) / 1000.0;
    x["p50_ms"] = static_cast<double>(l.quantile(0.5)) / 1000.0;
    x["p90_ms"] = static_cast<double>(l.quantile(0.9)) / 1000.0;
    x["p95_ms"] = static_cast<double>(l.quantile(0.95)) / 1000.0;
    x["p99_ms"] = static_cast<double>(l.quantile(0.99)) / 1000.0;
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
      y["periodic"] = t.periodic;
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

}  // namespace topdump::reference
