// The matrix loader's parsers of a step's parts: what it sends and each
// expectation it lists.
#include <memory>
#include <regex>

#include "matrix_json.hpp"
#include "top/motion.hpp"

namespace topconf::detail {

std::optional<SendSpec> parse_send(const Ctx& c, const json& o, const std::string& where) {
  if (!c.object(o, where,
                "must be an object ({\"raw\": ...}, {\"hex\": ...} or {\"command\": ...})"))
    return std::nullopt;
  SendSpec s;
  const std::string w = where + ".";
  if (o.contains("raw") || o.contains("hex")) {
    only_keys(c, o, where, {"raw", "hex"});
    s.raw = true;
    if (o.contains("hex")) {
      s.hex = true;
      if (!get_string(c, o, w, "hex", s.text, true)) return std::nullopt;
      if (!is_hex(s.text)) {
        c.err(w + "hex", "must be an even number of hex digits");
        return std::nullopt;
      }
    } else {
      if (!get_string(c, o, w, "raw", s.text, true)) return std::nullopt;
      if (s.text.empty() || s.text[0] != '#') {
        c.err(w + "raw", "a frame starts with '#'");
        return std::nullopt;
      }
    }
    return s;
  }
  only_keys(c, o, where, {"command", "control", "data", "data_hex", "src", "dst", "header"});
  if (!get_string(c, o, w, "command", s.command, true)) return std::nullopt;
  if (s.command.size() != 3) {
    c.err(w + "command", "must be a three-character identifier");
    return std::nullopt;
  }
  std::string ctl = "w";
  get_string(c, o, w, "control", ctl, false);
  if (ctl != "r" && ctl != "w") {
    c.err(w + "control", "must be \"r\" or \"w\"");
    return std::nullopt;
  }
  s.control = ctl[0];
  get_string(c, o, w, "data", s.data, false);
  std::string a;
  if (get_string(c, o, w, "data_hex", a, false)) {
    // Binary data (Topotek GPS/UAV structs) is written as hex.
    if (o.contains("data")) c.err(w + "data_hex", "give data or data_hex, not both");
    if (!is_hex(a)) {
      c.err(w + "data_hex", "must be an even number of hex digits");
      return std::nullopt;
    }
    s.data.clear();
    for (std::size_t i = 0; i < a.size(); i += 2)
      s.data.push_back(static_cast<char>(std::stoi(a.substr(i, 2), nullptr, 16)));
  }
  if (get_string(c, o, w, "src", a, false)) {
    if (a.size() != 1) {
      c.err(w + "src", "must be one address character");
      return std::nullopt;
    }
    s.src = a[0];
  }
  if (get_string(c, o, w, "dst", a, false)) {
    if (a.size() != 1) {
      c.err(w + "dst", "must be one address character");
      return std::nullopt;
    }
    s.dst = a[0];
  }
  if (get_string(c, o, w, "header", a, false)) {
    s.header = header_from(a);
    if (!s.header) {
      c.err(w + "header", "must be one of #TP #tp #tP #Tp");
      return std::nullopt;
    }
  }
  return s;
}

namespace {

// A regex checked and compiled once, at load; an error at `key` if invalid.
std::shared_ptr<const std::regex> compile(const Ctx& c, const std::string& key,
                                          const std::string& pattern) {
  try {
    return std::make_shared<const std::regex>(pattern);
  } catch (const std::regex_error&) {
    c.err(key, "not a valid regular expression");
    return nullptr;
  }
}

FieldCheck parse_field_check(const Ctx& c, const json& f, const std::string& fw,
                             const std::string& name) {
  FieldCheck fc;
  fc.name = name;
  only_keys(c, f, fw, {"min", "max", "enum", "pattern", "equals"});
  for (const char* k : {"min", "max"}) {
    if (auto v = f.find(k); v != f.end()) {
      if (!v->is_number())
        c.err(fw + "." + k, "must be a number");
      else
        (std::string_view(k) == "min" ? fc.min : fc.max) = v->get<double>();
    }
  }
  if (auto v = f.find("enum"); v != f.end()) {
    if (!v->is_array() || v->empty())
      c.err(fw + ".enum", "must be a non-empty array of names");
    else
      for (const auto& n : *v) {
        if (!n.is_string())
          c.err(fw + ".enum", "must hold strings");
        else
          fc.enums.push_back(n.get<std::string>());
      }
  }
  if (auto v = f.find("pattern"); v != f.end()) {
    if (!v->is_string()) {
      c.err(fw + ".pattern", "must be a string");
    } else {
      fc.pattern = v->get<std::string>();
      fc.re = compile(c, fw + ".pattern", fc.pattern);
    }
  }
  if (auto v = f.find("equals"); v != f.end()) {
    if (!v->is_string())
      c.err(fw + ".equals", "must be a string");
    else
      fc.equals = v->get<std::string>();
  }
  return fc;
}

bool parse_reply(const Ctx& c, const json& r, const std::string& w, Expectation& e) {
  const std::string rw = w + "reply.";
  if (!c.object(r, w + "reply")) return false;
  only_keys(c, r, w + "reply", {"ident", "control", "fields", "data_pattern", "data"});
  get_string(c, r, rw, "ident", e.ident, false);
  if (!e.ident.empty() && e.ident.size() != 3) c.err(rw + "ident", "must be three characters");
  std::string ctl;
  if (get_string(c, r, rw, "control", ctl, false)) {
    if (ctl != "r" && ctl != "w")
      c.err(rw + "control", "must be \"r\" or \"w\"");
    else
      e.control = ctl[0];
  }
  std::string d;
  if (get_string(c, r, rw, "data", d, false)) e.data = d;
  if (get_string(c, r, rw, "data_pattern", e.data_pattern, false))
    e.data_re = compile(c, rw + "data_pattern", e.data_pattern);
  if (auto it = r.find("fields"); it != r.end()) {
    if (!c.object(*it, rw + "fields", "must be an object of field checks")) return false;
    for (auto f = it->begin(); f != it->end(); ++f) {
      const std::string fw = rw + "fields." + f.key();
      if (!c.object(*f, fw, "must be an object (min, max, enum, pattern, equals)")) continue;
      e.fields.push_back(parse_field_check(c, *f, fw, f.key()));
    }
  }
  return true;
}

// A stream's "moves": {"axis": "yaw|pitch|roll", "sign": 1|-1, "min_deg": D}.
bool parse_moves(const Ctx& c, const json& m, const std::string& w, Expectation& e) {
  if (!c.object(m, w)) return false;
  only_keys(c, m, w, {"axis", "sign", "min_deg"});
  std::string axis;
  get_string(c, m, w + ".", "axis", axis, true);
  for (int a = 0; a < static_cast<int>(top::axis_count); ++a)
    if (axis == top::to_string(static_cast<top::Axis>(a))) e.move_axis = a;
  if (e.move_axis < 0) c.err(w + ".axis", "must be \"yaw\", \"pitch\" or \"roll\"");
  const auto sign = m.find("sign");
  if (sign == m.end() || !sign->is_number_integer() ||
      (sign->get<int>() != 1 && sign->get<int>() != -1))
    c.err(w + ".sign", "must be 1 or -1");
  else
    e.move_sign = sign->get<int>();
  const auto deg = m.find("min_deg");
  if (deg == m.end() || !deg->is_number() || deg->get<double>() <= 0 || deg->get<double>() > 180)
    c.err(w + ".min_deg", "must be a number above 0, at most 180");
  else
    e.move_min_deg = deg->get<double>();
  return e.move_axis >= 0 && e.move_sign != 0 && e.move_min_deg > 0;
}

bool parse_stream(const Ctx& c, const json& s, const std::string& w, Expectation& e) {
  const std::string sw = w + "stream.";
  if (!c.object(s, w + "stream")) return false;
  only_keys(
      c, s, w + "stream",
      {"ident", "rate_hz", "tolerance", "duration_ms", "data_pattern", "max_gap_ms", "moves"});
  if (!get_string(c, s, sw, "ident", e.ident, true)) return false;
  auto rate = s.find("rate_hz");
  if (rate == s.end() || !rate->is_number() || rate->get<double>() <= 0 ||
      rate->get<double>() > 1000) {
    c.err(sw + "rate_hz", "must be a number above 0, at most 1000");
    return false;
  }
  e.rate_hz = rate->get<double>();
  if (auto t = s.find("tolerance"); t != s.end()) {
    if (!t->is_number() || t->get<double>() < 0 || t->get<double>() > 1) {
      c.err(sw + "tolerance", "must be a fraction from 0 to 1");
      return false;
    }
    e.tolerance = t->get<double>();
  }
  if (!get_uint(c, s, sw, "duration_ms", e.duration_ms, 60000) || e.duration_ms == 0) {
    c.err(sw + "duration_ms", "must be an integer from 1 to 60000");
    return false;
  }
  // Only pushes whose data match count; no gap between them (from the
  // step's start to the window's end) may be longer than max_gap_ms.
  if (get_string(c, s, sw, "data_pattern", e.data_pattern, false))
    e.data_re = compile(c, sw + "data_pattern", e.data_pattern);
  if (s.contains("max_gap_ms") &&
      (!get_uint(c, s, sw, "max_gap_ms", e.max_gap_ms, 60000) || e.max_gap_ms == 0)) {
    c.err(sw + "max_gap_ms", "must be an integer from 1 to 60000");
    return false;
  }
  if (auto mv = s.find("moves"); mv != s.end()) return parse_moves(c, *mv, sw + "moves", e);
  return true;
}

bool parse_readback(const Ctx& c, const json& r, const std::string& w, Expectation& e) {
  if (!c.object(r, w + "readback")) return false;
  only_keys(c, r, w + "readback", {"send", "data"});
  if (!r.contains("send")) {
    c.err(w + "readback.send", "missing");
    return false;
  }
  auto s = parse_send(c, r["send"], w + "readback.send");
  if (!s) return false;
  e.read = *s;
  std::string d;
  if (get_string(c, r, w + "readback.", "data", d, false)) e.data = d;
  return true;
}

// The keys every kind of expectation takes: tolerated, addresses, note.
void parse_common(const Ctx& c, const json& o, const std::string& w, Expectation& e) {
  if (auto it = o.find("tolerated"); it != o.end()) {
    if (!it->is_boolean())
      c.err(w + "tolerated", "must be true or false");
    else
      e.tolerated = it->get<bool>();
  }
  std::string addr;
  if (get_string(c, o, w, "addresses", addr, false)) {
    if (addr != "swapped" && addr != "any")
      c.err(w + "addresses", "must be \"swapped\" or \"any\"");
    e.any_addresses = addr == "any";
  }
  get_string(c, o, w, "note", e.note, false);
}

}  // namespace

std::optional<Expectation> parse_expect(const Ctx& c, const json& o, const std::string& where) {
  if (!c.object(o, where)) return std::nullopt;
  Expectation e;
  const std::string w = where + ".";
  int kinds = 0;
  for (const char* k : {"frame", "echo", "reply", "error", "silence_ms", "stream", "readback"})
    kinds += o.contains(k) ? 1 : 0;
  if (kinds != 1) {
    c.err(where, "needs exactly one of frame, echo, reply, error, silence_ms, stream, readback");
    return std::nullopt;
  }
  only_keys(c, o, where,
            {"frame", "echo", "reply", "error", "silence_ms", "stream", "readback", "tolerated",
             "addresses", "note"});
  parse_common(c, o, w, e);
  bool ok = true;
  if (o.contains("frame")) {
    e.kind = ExpectKind::frame;
    std::string f;
    if (!get_string(c, o, w, "frame", f, true)) return std::nullopt;
    if (f.empty() || f[0] != '#') {
      c.err(w + "frame", "a frame starts with '#'");
      return std::nullopt;
    }
    e.frame.raw = true;
    e.frame.text = f;
  } else if (o.contains("echo") || o.contains("error")) {
    const char* k = o.contains("echo") ? "echo" : "error";
    if (!o[k].is_boolean() || !o[k].get<bool>()) {
      c.err(w + k, "must be true");
      return std::nullopt;
    }
    e.kind = o.contains("echo") ? ExpectKind::echo : ExpectKind::error;
  } else if (o.contains("silence_ms")) {
    e.kind = ExpectKind::silence;
    if (!get_uint(c, o, w, "silence_ms", e.silence_ms, 60000) || e.silence_ms == 0) {
      c.err(w + "silence_ms", "must be an integer from 1 to 60000");
      return std::nullopt;
    }
  } else if (o.contains("reply")) {
    e.kind = ExpectKind::reply;
    ok = parse_reply(c, o["reply"], w, e);
  } else if (o.contains("stream")) {
    e.kind = ExpectKind::stream;
    ok = parse_stream(c, o["stream"], w, e);
  } else {
    e.kind = ExpectKind::readback;
    ok = parse_readback(c, o["readback"], w, e);
  }
  if (!ok) return std::nullopt;
  return e;
}

}  // namespace topconf::detail
