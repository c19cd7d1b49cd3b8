// topdump wireshark: writes top.lua, a Wireshark dissector generated from the
// catalog (as pymavlink's `mavgen --lang=WLua` writes MAVLink's from its XML).
//
// The output is the catalog's tables as Lua (commands, forms, fields with
// kinds, widths, scales, units, ranges and enum labels; the finding codes as
// expert infos; the ports) followed by the fixed dissector of
// analyzer/wireshark/runtime/*.lua, which reads them. Every build writes it
// (BUILD/analyzer/top.lua); ctest compares tshark running it with `topdump
// read --json` on every bundled capture.
#include "wireshark/wireshark.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "top/detail/decimal.hpp"
#include "top/top.hpp"

namespace topdump {

extern const std::string_view kWiresharkRuntime;  // wireshark_runtime/*.lua, embedded by CMake

namespace {

// A Lua string literal: ASCII kept, the rest as decimal escapes.
std::string lua_str(std::string_view s) {
  std::string out = "\"";
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c >= 0x20 && c < 0x7F) {
      out += ch;
    } else {
      char b[8];
      std::snprintf(b, sizeof b, "\\%03u", c);
      out += b;
    }
  }
  return out + "\"";
}

// A double that Lua reads back exactly.
std::string lua_num(double v) {
  if (v == std::floor(v) && std::fabs(v) < 1e15) {
    char b[32];
    std::snprintf(b, sizeof b, "%.0f", v);
    return b;
  }
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// How a field's value is carried in Wireshark: "uint", "int", "double" or
// "string" (a field name that two forms type differently gets one type
// that holds both).
std::string value_type(const top::FieldSpec& s) {
  using K = top::FieldKind;
  if (top::is_integer_kind(s.kind)) {
    // An unscaled integer is a Lua integer: a binary one always, one of hex
    // or decimal digits when it has at most 8 hex or 9 decimal digits.
    const bool digits = s.kind == K::hex_u || s.kind == K::hex_s || s.kind == K::dec_u;
    const int most = s.kind == K::dec_u ? 9 : 8;
    if (s.scale != 1.0 || (digits && (s.width == 0 || s.width > most))) return "double";
    const bool is_signed =
        s.kind == K::hex_s || s.kind == K::le_i16 || s.kind == K::le_i32 || s.kind == K::be_i16;
    return is_signed ? "int" : "uint";
  }
  switch (s.kind) {
    case K::text:
    case K::raw:
      return "string";
    case K::number:
    case K::nmea:
      return "double";
    case K::enum_char:
      return "uint";
    case K::enum_hex:
      return s.width > 0 && s.width <= 8 ? "uint" : "double";
    default:
      break;
  }
  return "string";
}

std::string merge_types(const std::string& a, const std::string& b) {
  if (a == b) return a;
  if (a != "string" && b != "string") return "double";
  return "string";
}

struct FieldDecl {
  std::string abbrev, label, blurb, vtype, unit;
  std::map<std::int64_t, std::string> enums;
  bool hex = false;
};

std::string abbrev_of(const top::CommandSpec& c, const top::FieldSpec& s) {
  return "top." + std::string(c.ident) + "." + std::string(s.name);
}

std::vector<top::Dialect> dialects() { return {top::Dialect::skydroid, top::Dialect::topotek}; }

void write_fields(std::string& o) {
  std::map<std::string, FieldDecl> decls;
  std::vector<std::string> order;
  // A form's fields, then its records' (top.ODR.x for every record).
  auto each = [](const top::FormSpec& f, auto&& fn) {
    for (const top::FieldSpec& s : f.fields) fn(s);
    for (const top::FieldSpec& s : f.record) fn(s);
  };
  for (top::Dialect d : dialects())
    for (const top::CommandSpec& c : top::commands(d))
      for (const top::FormSpec& f : c.forms)
        each(f, [&](const top::FieldSpec& s) {
          const std::string ab = abbrev_of(c, s);
          auto [it, fresh] = decls.try_emplace(ab);
          FieldDecl& x = it->second;
          if (fresh) {
            order.push_back(ab);
            x.abbrev = ab;
            x.label = std::string(c.ident) + " " + std::string(s.name);
            x.unit = std::string(s.unit);
            if (!s.unit.empty()) x.label += " (" + std::string(s.unit) + ")";
            x.blurb = std::string(c.title) + " (" + std::string(c.section) + ")";
            if (!s.note.empty()) x.blurb += ": " + std::string(s.note);
            x.vtype = value_type(s);
            x.hex = s.kind == top::FieldKind::enum_hex;
          } else {
            x.vtype = merge_types(x.vtype, value_type(s));
          }
          for (const top::EnumValue& e : s.enums) x.enums.try_emplace(e.value, std::string(e.name));
        });
  o += "-- Every catalog field as top.<ident>.<field>.\nlocal CATALOG_FIELDS = {}\n";
  for (const std::string& ab : order) {
    const FieldDecl& x = decls[ab];
    std::string type = x.vtype == "uint"     ? "ftypes.UINT32"
                       : x.vtype == "int"    ? "ftypes.INT32"
                       : x.vtype == "double" ? "ftypes.DOUBLE"
                                             : "ftypes.STRING";
    std::string vs = "nil", base = "nil";
    if (x.vtype == "uint" || x.vtype == "int") {
      base = x.hex ? "base.HEX" : "base.DEC";
      if (!x.enums.empty()) {
        vs = "{";
        for (const auto& [v, name] : x.enums)
          vs += " [" + std::to_string(v) + "] = " + lua_str(name) + ",";
        vs += " }";
      }
    } else if (x.vtype == "string") {
      base = "base.ASCII";
    }
    o += "CATALOG_FIELDS[" + lua_str(ab) + "] = ProtoField.new(" + lua_str(x.label) + ", " +
         lua_str(ab) + ", " + type + ", " + vs + ", " + base + ", nil, " + lua_str(x.blurb) + ")\n";
    o += "CATALOG_VTYPE[" + lua_str(ab) + "] = " + lua_str(x.vtype) + "\n";
  }
}

std::string field_spec(const top::CommandSpec& c, const top::FieldSpec& s) {
  std::string o = "{ name = " + lua_str(s.name) + ", kind = " + lua_str(top::to_string(s.kind)) +
                  ", width = " + std::to_string(s.width) + ", scale = " + lua_num(s.scale);
  // The scale as m / 10^d when it is a decimal fraction, so Lua computes the
  // same correctly rounded value as decode.cpp's scaled().
  const int d = top::detail::decimals_of(s.scale);
  const double m = s.scale * std::pow(10.0, d);
  if (s.scale > 0 && std::fabs(m - std::round(m)) <= 1e-9 && m <= 1e9)
    o += ", mul = " + lua_num(std::round(m));
  o += ", dec = " + std::to_string(d);
  o += ", unit = " + lua_str(s.unit);
  if (s.min <= s.max) o += ", min = " + lua_num(s.min) + ", max = " + lua_num(s.max);
  if (!s.enums.empty()) {
    o += ", enums = {";
    for (const top::EnumValue& e : s.enums)
      o += " [" + std::to_string(e.value) + "] = " + lua_str(e.name) + ",";
    o += " }";
  }
  if (!s.none.empty()) o += ", none = " + lua_str(s.none);
  o += ", abbrev = " + lua_str(abbrev_of(c, s)) + " }";
  return o;
}

void write_catalog(std::string& o) {
  o += "\n-- The command catalog of both dialects (protocol/src/catalog_*.cpp).\n";
  o += "local CATALOG = { skydroid = {}, topotek = {} }\n";
  for (top::Dialect d : dialects())
    for (const top::CommandSpec& c : top::commands(d)) {
      std::string models;
      for (top::Model m : top::all_models())
        if (c.models & top::model_bit(m))
          models += " " + std::string(top::to_string(m)) + " = true,";
      o += "CATALOG." + std::string(top::to_string(d)) + "[" + lua_str(c.ident) +
           "] = {\n  dialect = " + lua_str(top::to_string(d)) +
           ", address = " + lua_str(std::string(1, c.address)) + ", title = " + lua_str(c.title) +
           ", section = " + lua_str(c.section) + (c.from_field() ? ", field = true" : "") +
           ",\n  models = {" + models + " },\n  forms = {\n";
      for (const top::FormSpec& f : c.forms) {
        o += "    { control = " + lua_str(std::string(1, f.control)) +
             ", role = " + lua_str(top::to_string(f.role)) +
             ", min_length = " + std::to_string(f.min_length) +
             ", max_length = " + std::to_string(f.max_length) + ", note = " + lua_str(f.note);
        if (!f.none.empty()) o += ", none = " + lua_str(f.none);
        if (f.from_field()) o += ", evidence = " + lua_str(f.evidence);
        o += ",\n      fields = {\n";
        for (const top::FieldSpec& s : f.fields) o += "        " + field_spec(c, s) + ",\n";
        o += "      }";
        if (!f.record.empty()) {
          o += ",\n      record = {\n";
          for (const top::FieldSpec& s : f.record) o += "        " + field_spec(c, s) + ",\n";
          o += "      }";
        }
        o += " },\n";
      }
      o += "  },\n}\n";
    }
}

void write_findings(std::string& o) {
  o += "\n-- The finding codes (protocol/include/top/findings.hpp) as expert infos:\n"
       "-- top.finding.<code> at the default severity, top.finding.<code>.<severity>\n"
       "-- when a frame's finding has another one; QUIRKS: the firmware quirk a code names.\n";
  o += "local FINDINGS, EXPERTS, QUIRKS = {}, {}, {}\n";
  const char* sev_names[] = {"info", "warning", "error"};
  const char* sev_lua[] = {"expert.severity.NOTE", "expert.severity.WARN", "expert.severity.ERROR"};
  for (std::size_t i = 0; i < top::finding_code_count; ++i) {
    const auto code = static_cast<top::FindingCode>(i);
    const std::string name(top::to_string(code));
    const auto def = static_cast<std::size_t>(top::default_severity(code));
    std::string group = "expert.group.PROTOCOL";
    if (name.find("checksum") != std::string::npos)
      group = "expert.group.CHECKSUM";
    else if (name.rfind("bad-", 0) == 0 || name == "truncated" || name == "frame-too-long")
      group = "expert.group.MALFORMED";
    o += "FINDINGS[" + lua_str(name) + "] = " + lua_str(sev_names[def]) + "\n";
    if (const std::string_view q = top::quirk_id(code); !q.empty())
      o += "QUIRKS[" + lua_str(name) + "] = " + lua_str(std::string(q)) + "\n";
    o += "EXPERTS[" + lua_str(name) + "] = {\n";
    for (std::size_t s = 0; s < 3; ++s) {
      std::string ab = "top.finding." + name + (s == def ? "" : "." + std::string(sev_names[s]));
      o += "  [" + lua_str(sev_names[s]) + "] = ProtoExpert.new(" + lua_str(ab) + ", " +
           lua_str(name + ": " + std::string(top::description(code))) + ", " + group + ", " +
           sev_lua[s] + "),\n";
    }
    o += "}\n";
  }
}

void write_ports(std::string& o) {
  o += "\n-- The known ports and the dialect each implies (top::dialect_from_port).\n";
  std::string udp, tcp, dialect;
  std::map<std::uint16_t, bool> done;
  for (const top::PortSpec& p : top::known_ports()) {  // the library's one table
    (p.tcp ? tcp : udp) += " " + std::to_string(p.port) + ",";
    if (done[p.port]) continue;
    done[p.port] = true;
    const top::Dialect d = top::dialect_from_port(p.port);
    if (d != top::Dialect::unknown)
      dialect += " [" + std::to_string(p.port) + "] = " + lua_str(top::to_string(d)) + ",";
  }
  o += "local PORTS = { udp = {" + udp + " }, tcp = {" + tcp + " } }\n";
  o += "local PORT_DIALECT = {" + dialect + " }\n";
  std::string models, model_dialect;
  for (top::Model m : top::all_models()) {
    models += " " + lua_str(top::to_string(m)) + ",";
    model_dialect += " " + std::string(top::to_string(m)) + " = " +
                     lua_str(top::to_string(top::dialect_of(m))) + ",";
  }
  o += "local MODELS = {" + models + " }\n";
  o += "local MODEL_DIALECT = {" + model_dialect + " }\n";
}

// What the dissector needs to tell the device end of a conversation as
// topdump does (analyzer/session: learn_device) and to name the form a
// device frame is recorded in (top::note_device_form): the role of each
// known port, the streams (which identifier a device pushes, which write
// switches one) and every recorded device form.
void write_roles(std::string& o) {
  o += "\n-- The end of a conversation each known port belongs to (top::port_role).\n";
  std::string roles;
  std::map<std::uint16_t, bool> done;
  for (const top::PortSpec& p : top::known_ports()) {
    if (done[p.port]) continue;
    done[p.port] = true;
    const top::PortRole r = top::port_role(p.port);
    if (r != top::PortRole::unknown)
      roles += " [" + std::to_string(p.port) +
               "] = " + lua_str(r == top::PortRole::device ? "device" : "client") + ",";
  }
  o += "local PORT_ROLE = {" + roles + " }\n";
  o += "\n-- The streams (top::streams()): the sender of each pushed identifier (the first\n"
       "-- stream that names it, as top::stream_of), and the writes that switch one.\n";
  o +=
      "local STREAMS = { skydroid = { push = {}, switch = {} }, topotek = { push = {}, switch = {} "
      "} }\n";
  std::map<std::string, bool> pushed;
  for (const top::StreamSpec& s : top::streams()) {
    const std::string d(top::to_string(s.dialect));
    if (!pushed[d + " " + std::string(s.push)]) {
      pushed[d + " " + std::string(s.push)] = true;
      o += "STREAMS." + d + ".push[" + lua_str(s.push) +
           "] = " + lua_str(s.sender == top::Sender::device ? "device" : "client") + "\n";
    }
    o += "STREAMS." + d + ".switch[" + lua_str(s.request) + "] = true\n";
  }
  o += "\n-- Every recorded device form (top::device_forms()): document examples and\n"
       "-- field evidence of the header and address order a device frame comes in.\n";
  o += "local RECORDED = {\n";
  // top::Header as frame.lua names it
  constexpr const char* kHeaderName[] = {"fixed", "variable", "ext8", "ext16", "tmp"};
  static_assert(std::size(kHeaderName) == static_cast<std::size_t>(top::Header::tmp_quirk) + 1);
  for (const top::DeviceForm& f : top::device_forms()) {
    std::string models;
    for (top::Model m : top::all_models())
      if (f.models & top::model_bit(m)) models += " " + std::string(top::to_string(m)) + " = true,";
    o += "  { dialect = " + lua_str(top::to_string(f.dialect)) + ", models = {" + models +
         " }, ident = " + lua_str(f.ident) + ", control = " + lua_str(std::string(1, f.control)) +
         ", sent = " + lua_str(f.sent == top::Sent::push ? "push" : "reply") +
         ", header = " + lua_str(kHeaderName[static_cast<std::size_t>(f.header)]) +
         ", order = " + lua_str(top::to_string(f.order)) +
         ", source = " + lua_str(top::to_string(f.source)) + ", evidence = " + lua_str(f.evidence) +
         " },\n";
  }
  o += "}\n";
}

}  // namespace

std::string wireshark_lua() {
  std::string o;
  o += "-- top.lua: a Wireshark/tshark dissector for the TOP gimbal-camera protocol\n"
       "-- (SkyDroid and Topotek).\n"
       "--\n"
       "-- GENERATED by `topdump wireshark` from the TOPKit command catalog; do not\n"
       "-- edit. Install: topdump wireshark > ~/.local/lib/wireshark/plugins/top.lua\n"
       "-- (docs/WIRESHARK.md).\n"
       "-- Needs Wireshark 3.6 or later (Lua 5.2).\n\n"
       "local top = Proto(\"top\", \"TOP gimbal-camera protocol\")\n";
  write_ports(o);
  write_roles(o);
  write_findings(o);
  o += "\nlocal CATALOG_VTYPE = {}\n";
  write_fields(o);
  write_catalog(o);
  o += "\n";
  o += kWiresharkRuntime;
  return o;
}

}  // namespace topdump
