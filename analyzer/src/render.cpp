#include "render.hpp"

#include <algorithm>
#include <cstdio>

#include "escape.hpp"

namespace topdump {

std::vector<const top::Finding*> all_findings(const top::Frame& f, const top::Decoded& d) {
  std::vector<const top::Finding*> v;
  v.reserve(f.findings.size() + d.findings.size());
  for (const auto& x : f.findings) v.push_back(&x);
  for (const auto& x : d.findings) v.push_back(&x);
  std::stable_sort(v.begin(), v.end(), [](const top::Finding* a, const top::Finding* b) {
    return a->offset < b->offset;
  });
  return v;
}

top::Severity worst(const top::Frame& f, const top::Decoded& d) {
  top::Severity w = f.worst();
  for (const auto& x : d.findings)
    if (x.severity > w) w = x.severity;
  return w;
}

std::string address_name(char a) {
  switch (a) {
    case 'U':
      return "U (UART/UDP client)";
    case 'M':
      return "M (lens)";
    case 'D':
      return "D (system/image)";
    case 'E':
      return "E (auxiliary)";
    case 'P':
      return "P (network client)";
    case 'G':
      return "G (gimbal)";
  }
  return escape(std::string(1, a));
}

namespace {

std::string hex2(std::uint8_t v) {
  char b[3];
  top::put_hex2(v, b);
  b[2] = 0;
  return b;
}

std::string_view role_name(top::Role r) {
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

json field_json(const top::FieldValue& v, const top::Frame& f) {
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

json finding_json(const top::Finding& x) {
  json j;
  j["code"] = top::to_string(x.code);
  j["severity"] = top::to_string(x.severity);
  j["offset"] = x.offset;
  j["message"] = escape(x.message);
  if (!x.quirk.empty()) j["quirk"] = x.quirk;
  return j;
}

}  // namespace

json frame_json(const top::Frame& f, const top::Decoded& d) {
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
  j["role"] = role_name(d.role);
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
  for (const auto& v : d.fields) fields[std::string(v.name())] = field_json(v, f);
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

json garbage_json(const top::StreamItem& g) {
  json j;
  j["garbage"] = true;
  j["length"] = g.length;
  j["preview"] = escape(g.preview);
  j["findings"] = json::array({finding_json(g.finding)});
  j["ok"] = g.finding.severity != top::Severity::error;
  return j;
}

std::string finding_line(const top::Finding& x) {
  char b[32];
  std::snprintf(b, sizeof b, "%-7s ", std::string(top::to_string(x.severity)).c_str());
  std::string s = b;
  s += top::to_string(x.code);
  s += " @" + std::to_string(x.offset) + ": " + x.message;
  if (!x.quirk.empty()) s += " [quirk: " + std::string(x.quirk) + "]";
  return s;
}

std::string frame_tree(const top::Frame& f, const top::Decoded& d) {
  std::string s;
  auto line = [&](const std::string& t) { s += "  " + t + "\n"; };
  static constexpr const char* kHeaderKind[] = {
      "fixed, length 2", "variable, one hex length char", "extended, one raw length byte",
      "extended, two raw length bytes", "malformed Topotek TMP form"};
  line("header   " + escape(f.header_text()) + " (" + kHeaderKind[static_cast<int>(f.header)] +
       ")   @0");
  line("src      " + address_name(f.src));
  line("dst      " + address_name(f.dst));
  std::string len = "length   " + std::to_string(f.data_length);
  if (f.declared_length != f.data_length)
    len += " (declared " + std::to_string(f.declared_length) + ")";
  line(len);
  if (f.control)
    line(std::string("control  ") + f.control + (f.control == 'r' ? " (query)" : " (set/control)"));
  std::string id = "ident    " + std::string(f.ident_view());
  if (d.command)
    id += ": " + std::string(d.command->title) + " [" + std::string(d.command->section) + ", " +
          std::string(top::to_string(d.dialect)) + " " + std::string(role_name(d.role)) + "]";
  line(id);
  line("data     \"" + escape(f.data()) + "\"");
  std::size_t width = 0;
  for (const auto& v : d.fields) width = std::max(width, v.name().size());
  for (const auto& v : d.fields) {
    std::string n(v.name());
    n.resize(width, ' ');
    line("  " + n + "  " + format_value(v) + "   @" + std::to_string(v.offset) + " \"" +
         escape(std::string_view(f.raw).substr(v.offset, v.length)) + "\"");
  }
  if (f.checksum_present) {
    std::string c = "checksum " + escape(f.checksum_text());
    c += f.checksum_ok ? " (ok)" : " (expected " + hex2(f.expected_checksum) + ")";
    line(c);
  } else {
    line("checksum missing (expected " + hex2(f.expected_checksum) + ")");
  }
  for (const top::Finding* x : all_findings(f, d)) line(finding_line(*x));
  return s;
}

}  // namespace topdump
