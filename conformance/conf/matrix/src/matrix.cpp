#include "conf/matrix.hpp"

#include <iterator>
#include <nlohmann/json.hpp>
#include <set>

#include "matrix_json.hpp"
#include "top/enum_names.hpp"

namespace topconf {
namespace {

using namespace detail;

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
