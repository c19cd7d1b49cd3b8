#include "conf/matrix.hpp"

#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "top/enum_names.hpp"

namespace topconf {
namespace {

using json = nlohmann::json;

struct Ctx {
  std::string file;
  std::string case_id;
  std::vector<std::string>* errors;
  void err(const std::string& key, const std::string& msg) const {
    std::string s = file + ": ";
    if (!case_id.empty()) s += "case " + case_id + ": ";
    s += key + ": " + msg;
    if (errors->size() < 200) errors->push_back(std::move(s));
  }
  // Whether `o` is a JSON object; an error at `key` if not (`msg`: what it
  // must be).
  bool object(const json& o, const std::string& key,
              const std::string& msg = "must be an object") const {
    if (!o.is_object()) err(key, msg);
    return o.is_object();
  }
};

// nlohmann's DOM parser with its errors returned instead of thrown: a syntax
// error is a parse_error, but a number too large for a double (3e7043) is an
// out_of_range (406) that carries no position. Both reach parse_error() here
// with the byte offset.
class Sax : public nlohmann::detail::json_sax_dom_parser<json> {
 public:
  explicit Sax(json& doc) : json_sax_dom_parser(doc, false) {}
  bool parse_error(std::size_t byte, const std::string& /*token*/,
                   const nlohmann::detail::exception& e) {
    error = "not valid JSON at byte " + std::to_string(byte) + ": " + e.what();
    return false;
  }
  std::string error;
};

std::optional<std::string> parse_json(std::string_view text, json& doc) {
  Sax sax(doc);
  if (!json::sax_parse(text.begin(), text.end(), &sax) || !sax.error.empty())
    return sax.error.empty() ? std::string("not valid JSON") : sax.error;
  return std::nullopt;
}

void only_keys(const Ctx& c, const json& o, const std::string& where,
               std::initializer_list<std::string_view> keys) {
  for (auto it = o.begin(); it != o.end(); ++it) {
    bool ok = false;
    for (auto k : keys) ok = ok || it.key() == k;
    if (!ok) c.err(where + (where.empty() ? "" : ".") + it.key(), "unknown key");
  }
}

bool get_string(const Ctx& c, const json& o, const std::string& where, const char* key,
                std::string& out, bool required) {
  auto it = o.find(key);
  if (it == o.end()) {
    if (required) c.err(where + key, "missing (a string is required)");
    return false;
  }
  if (!it->is_string()) {
    c.err(where + key, "must be a string");
    return false;
  }
  out = it->get<std::string>();
  return true;
}

bool get_uint(const Ctx& c, const json& o, const std::string& where, const char* key,
              std::uint32_t& out, std::uint32_t max) {
  auto it = o.find(key);
  if (it == o.end()) return false;
  if (!it->is_number_unsigned() || it->get<std::uint64_t>() > max) {
    c.err(where + key, "must be an integer from 0 to " + std::to_string(max));
    return false;
  }
  out = static_cast<std::uint32_t>(it->get<std::uint64_t>());
  return true;
}

// A header a step can build (not the TMP form).
std::optional<top::Header> header_from(std::string_view s) {
  const auto h = top::header_from_string(s);
  if (h == top::Header::tmp_quirk) return std::nullopt;
  return h;
}

bool is_hex(std::string_view s) {
  if (s.size() % 2) return false;
  for (char ch : s)
    if (!std::isxdigit(static_cast<unsigned char>(ch))) return false;
  return true;
}

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
    const json& r = o["reply"];
    const std::string rw = w + "reply.";
    if (!c.object(r, w + "reply")) return std::nullopt;
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
    if (get_string(c, r, rw, "data_pattern", e.data_pattern, false)) {
      try {
        std::regex re(e.data_pattern);
      } catch (const std::regex_error&) {
        c.err(rw + "data_pattern", "not a valid regular expression");
      }
    }
    if (auto it = r.find("fields"); it != r.end()) {
      if (!c.object(*it, rw + "fields", "must be an object of field checks")) return std::nullopt;
      for (auto f = it->begin(); f != it->end(); ++f) {
        const std::string fw = rw + "fields." + f.key();
        FieldCheck fc;
        fc.name = f.key();
        if (!c.object(*f, fw, "must be an object (min, max, enum, pattern, equals)")) continue;
        only_keys(c, *f, fw, {"min", "max", "enum", "pattern", "equals"});
        for (const char* k : {"min", "max"}) {
          if (auto v = f->find(k); v != f->end()) {
            if (!v->is_number())
              c.err(fw + "." + k, "must be a number");
            else
              (std::string_view(k) == "min" ? fc.min : fc.max) = v->get<double>();
          }
        }
        if (auto v = f->find("enum"); v != f->end()) {
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
        if (auto v = f->find("pattern"); v != f->end()) {
          if (!v->is_string())
            c.err(fw + ".pattern", "must be a string");
          else {
            fc.pattern = v->get<std::string>();
            try {
              std::regex re(fc.pattern);
            } catch (const std::regex_error&) {
              c.err(fw + ".pattern", "not a valid regular expression");
            }
          }
        }
        if (auto v = f->find("equals"); v != f->end()) {
          if (!v->is_string())
            c.err(fw + ".equals", "must be a string");
          else
            fc.equals = v->get<std::string>();
        }
        e.fields.push_back(std::move(fc));
      }
    }
  } else if (o.contains("stream")) {
    e.kind = ExpectKind::stream;
    const json& s = o["stream"];
    const std::string sw = w + "stream.";
    if (!c.object(s, w + "stream")) return std::nullopt;
    only_keys(c, s, w + "stream", {"ident", "rate_hz", "tolerance", "duration_ms"});
    if (!get_string(c, s, sw, "ident", e.ident, true)) return std::nullopt;
    auto rate = s.find("rate_hz");
    if (rate == s.end() || !rate->is_number() || rate->get<double>() <= 0 ||
        rate->get<double>() > 1000) {
      c.err(sw + "rate_hz", "must be a number above 0, at most 1000");
      return std::nullopt;
    }
    e.rate_hz = rate->get<double>();
    if (auto t = s.find("tolerance"); t != s.end()) {
      if (!t->is_number() || t->get<double>() < 0 || t->get<double>() > 1) {
        c.err(sw + "tolerance", "must be a fraction from 0 to 1");
        return std::nullopt;
      }
      e.tolerance = t->get<double>();
    }
    if (!get_uint(c, s, sw, "duration_ms", e.duration_ms, 60000) || e.duration_ms == 0) {
      c.err(sw + "duration_ms", "must be an integer from 1 to 60000");
      return std::nullopt;
    }
  } else {
    e.kind = ExpectKind::readback;
    const json& r = o["readback"];
    if (!c.object(r, w + "readback")) return std::nullopt;
    only_keys(c, r, w + "readback", {"send", "data"});
    if (!r.contains("send")) {
      c.err(w + "readback.send", "missing");
      return std::nullopt;
    }
    auto s = parse_send(c, r["send"], w + "readback.send");
    if (!s) return std::nullopt;
    e.read = *s;
    std::string d;
    if (get_string(c, r, w + "readback.", "data", d, false)) e.data = d;
  }
  return e;
}

std::optional<Step> parse_step(const Ctx& c, const json& o, const std::string& where) {
  if (!c.object(o, where)) return std::nullopt;
  only_keys(c, o, where, {"send", "expect", "timeout_ms"});
  Step s;
  const std::string w = where + ".";
  if (o.contains("send")) {
    s.send = parse_send(c, o["send"], w + "send");
    if (!s.send) return std::nullopt;
  }
  get_uint(c, o, w, "timeout_ms", s.timeout_ms, 60000);
  auto ex = o.find("expect");
  if (ex == o.end() || !ex->is_array() || ex->empty()) {
    c.err(w + "expect", "must be a non-empty array of alternatives");
    return std::nullopt;
  }
  for (std::size_t i = 0; i < ex->size(); ++i) {
    auto e = parse_expect(c, (*ex)[i], w + "expect[" + std::to_string(i) + "]");
    if (e) s.expect.push_back(std::move(*e));
  }
  bool has_readback = false;
  for (const auto& e : s.expect) has_readback = has_readback || e.kind == ExpectKind::readback;
  if (has_readback && !s.send) c.err(w + "expect", "a readback needs the step to send a write");
  const bool needs_send = std::any_of(s.expect.begin(), s.expect.end(), [](const Expectation& e) {
    return e.kind == ExpectKind::echo || e.kind == ExpectKind::error ||
           e.kind == ExpectKind::readback;
  });
  if (needs_send && !s.send) c.err(w + "expect", "echo, error and readback need the step to send");
  return s;
}

void parse_steps(const Ctx& c, const json& o, const char* key, std::vector<Step>& out,
                 bool required) {
  auto it = o.find(key);
  if (it == o.end()) {
    if (required) c.err(key, "missing (a non-empty array of steps)");
    return;
  }
  if (!it->is_array() || (required && it->empty())) {
    c.err(key, "must be a non-empty array of steps");
    return;
  }
  for (std::size_t i = 0; i < it->size(); ++i) {
    auto s = parse_step(c, (*it)[i], std::string(key) + "[" + std::to_string(i) + "]");
    if (s) out.push_back(std::move(*s));
  }
}

}  // namespace

namespace {
constexpr std::string_view kLevel[] = {"must", "should", "may"};
static_assert(std::size(kLevel) == static_cast<std::size_t>(Level::may) + 1);
constexpr std::string_view kExpectKind[] = {"frame",   "echo",   "reply",   "error",
                                            "silence", "stream", "readback"};
static_assert(std::size(kExpectKind) == static_cast<std::size_t>(ExpectKind::readback) + 1);
}  // namespace

std::string_view to_string(Level l) noexcept { return top::enum_name(kLevel, l); }

std::optional<Level> level_from_string(std::string_view s) noexcept {
  return top::enum_from_name<Level>(kLevel, s);
}

std::string_view to_string(ExpectKind k) noexcept { return top::enum_name(kExpectKind, k); }

bool Case::applies_to(top::Model m) const noexcept {
  if (models.empty()) return true;
  for (auto x : models)
    if (x == m) return true;
  return false;
}

LoadResult load_matrix(std::string_view text, std::string_view file) {
  LoadResult res;
  Ctx c{std::string(file), "", &res.errors};
  json doc;
  if (auto bad = parse_json(text, doc)) {
    c.err("(json)", *bad);
    return res;
  }
  if (!c.object(doc, "(root)")) return res;
  only_keys(c, doc, "",
            {"$schema", "format", "title", "model", "document", "defaults", "probe", "cases"});
  Matrix m;
  m.file = std::string(file);
  std::string fmt;
  if (get_string(c, doc, "", "format", fmt, true) && fmt != "topconf-matrix-1")
    c.err("format", "must be \"topconf-matrix-1\"");
  get_string(c, doc, "", "title", m.title, false);
  std::string model;
  if (get_string(c, doc, "", "model", model, true)) {
    auto mm = top::model_from_string(model);
    if (!mm || *mm == top::Model::unknown)
      c.err("model", "must be one of " + top::model_list());
    else {
      m.model = *mm;
      m.dialect = top::dialect_of(*mm);
    }
  }
  if (auto d = doc.find("defaults"); d != doc.end()) {
    if (!d->is_object())
      c.err("defaults", "must be an object");
    else {
      only_keys(c, *d, "defaults", {"timeout_ms", "retries", "settle_ms", "probe_timeout_ms"});
      get_uint(c, *d, "defaults.", "timeout_ms", m.timeout_ms, 60000);
      get_uint(c, *d, "defaults.", "retries", m.retries, 10);
      get_uint(c, *d, "defaults.", "settle_ms", m.settle_ms, 10000);
      get_uint(c, *d, "defaults.", "probe_timeout_ms", m.probe_timeout_ms, 60000);
    }
  }
  if (doc.contains("probe")) m.probe = parse_send(c, doc["probe"], "probe");
  auto cases = doc.find("cases");
  if (cases == doc.end() || !cases->is_array()) {
    c.err("cases", "missing (an array of cases)");
    return res;
  }
  std::set<std::string> ids;
  for (std::size_t i = 0; i < cases->size(); ++i) {
    const json& o = (*cases)[i];
    Ctx cc = c;
    cc.case_id = "#" + std::to_string(i);
    if (!cc.object(o, "(case)")) continue;
    Case k;
    if (get_string(cc, o, "", "id", k.id, true)) {
      cc.case_id = k.id;
      if (k.id.empty()) cc.err("id", "must not be empty");
      if (!ids.insert(k.id).second) cc.err("id", "duplicate case id");
    }
    only_keys(cc, o, "",
              {"id", "section", "title", "level", "models", "tags", "preconditions", "steps",
               "timeout_ms", "retries", "note"});
    get_string(cc, o, "", "section", k.section, true);
    get_string(cc, o, "", "title", k.title, false);
    std::string lv;
    if (get_string(cc, o, "", "level", lv, true)) {
      auto l = level_from_string(lv);
      if (!l)
        cc.err("level", "must be must, should or may");
      else
        k.level = *l;
    }
    if (auto ms = o.find("models"); ms != o.end()) {
      if (!ms->is_array())
        cc.err("models", "must be an array of model names");
      else
        for (const auto& n : *ms) {
          auto mm = n.is_string() ? top::model_from_string(n.get<std::string>()) : std::nullopt;
          if (!mm || *mm == top::Model::unknown)
            cc.err("models", "unknown model " + n.dump());
          else
            k.models.push_back(*mm);
        }
    }
    if (auto ts = o.find("tags"); ts != o.end()) {
      if (!ts->is_array())
        cc.err("tags", "must be an array of strings");
      else
        for (const auto& n : *ts) {
          if (!n.is_string())
            cc.err("tags", "must hold strings");
          else
            k.tags.push_back(n.get<std::string>());
        }
    }
    std::uint32_t r = 0;
    if (get_uint(cc, o, "", "retries", r, 10)) k.retries = static_cast<std::int32_t>(r);
    get_uint(cc, o, "", "timeout_ms", k.timeout_ms, 60000);
    parse_steps(cc, o, "preconditions", k.preconditions, false);
    parse_steps(cc, o, "steps", k.steps, true);
    m.cases.push_back(std::move(k));
  }
  if (res.errors.empty()) res.matrix = std::move(m);
  return res;
}

bool resolve_send(const SendSpec& s, top::Dialect dialect, char client, std::string& bytes,
                  std::string& error) {
  if (s.raw && s.hex) {
    bytes.clear();
    for (std::size_t i = 0; i + 1 < s.text.size(); i += 2)
      bytes.push_back(static_cast<char>(std::stoi(s.text.substr(i, 2), nullptr, 16)));
    return true;
  }
  if (s.raw) {
    std::string t = s.text;
    for (std::size_t p; (p = t.find("{client}")) != std::string::npos;) t.replace(p, 8, 1, client);
    // The checksum is added when absent: the text parses only with it.
    auto r = top::parse_exact(t);
    if (r.status == top::ParseStatus::frame && r.frame.checksum_present &&
        !r.frame.has(top::FindingCode::no_checksum)) {
      bytes = t;
      return true;
    }
    std::string with = top::with_checksum(t);
    auto r2 = top::parse_exact(with);
    if (r2.status == top::ParseStatus::frame) {
      bytes = with;
      return true;
    }
    bytes = t;  // sent as written: the case wants a malformed frame
    return true;
  }
  const top::CommandSpec* cmd = top::find_command(dialect, s.command);
  top::BuildSpec b;
  b.src = s.src ? s.src : client;
  b.dst = s.dst ? s.dst : (cmd ? cmd->address : 'D');
  b.control = s.control;
  b.ident = s.command;
  b.data = s.data;
  b.header =
      s.header ? *s.header : top::choose_header(dialect, cmd ? cmd->address : b.dst, s.data.size());
  if (s.data.size() > top::max_data_ext16) {
    error = "data too long";
    return false;
  }
  bytes = top::build_frame(b);
  return true;
}

}  // namespace topconf
