#include "conf/generate.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace topconf {
namespace {

using json = nlohmann::ordered_json;
using top::Dialect;
using top::FieldKind;

std::string section_number(std::string_view section) {
  // "SkyDroid 3.3.1" -> "3.3.1"; "SkyDroid appendix I" -> "appendix-I"
  auto sp = section.find(' ');
  std::string s(sp == std::string_view::npos ? section : section.substr(sp + 1));
  for (char& c : s)
    if (c == ' ') c = '-';
  return s;
}

const top::FormSpec* find_form(const top::CommandSpec& c, char control, top::Role role) {
  for (const auto& f : c.forms)
    if (f.control == control && (f.role == role || f.role == top::Role::any)) return &f;
  return nullptr;
}

bool clean_request(Dialect d, top::Model m, const top::CommandSpec& c, char control,
                   const std::string& data) {
  top::BuildSpec b;
  b.src = d == Dialect::topotek ? 'P' : 'U';
  b.dst = c.address;
  b.control = control;
  b.ident = c.ident;
  b.data = data;
  b.header = top::choose_header(d, c.address, data.size());
  auto p = top::parse_exact(top::build_frame(b));
  if (p.status != top::ParseStatus::frame || !p.frame.ok()) return false;
  top::DecodeOptions o;
  o.dialect = d;
  o.model = m;
  o.role = top::Role::request;
  auto dec = top::decode(p.frame, o);
  if (!dec.form) return false;
  for (const auto& f : dec.findings)
    if (f.severity != top::Severity::info) return false;
  return true;
}

// Data for a write that differs from the device's default where it can:
// the first enum value or the low end of each range.
std::string alternate_data(const top::FormSpec& form) {
  std::vector<top::EncodeValue> vals;
  std::vector<std::string> texts;
  texts.reserve(form.fields.size());
  for (const auto& f : form.fields) {
    top::EncodeValue v;
    switch (f.kind) {
      case FieldKind::enum_hex:
      case FieldKind::enum_char:
        if (!f.enums.empty()) v.number = static_cast<double>(f.enums.front().value);
        break;
      case FieldKind::text:
        texts.push_back(f.width == 0 ? "10.0.0.9" : std::string(f.width, 'B'));
        v.text = texts.back();
        v.use_text = true;
        break;
      case FieldKind::raw:
      case FieldKind::nmea:
        return top::example_data(form);
      default:
        v.number = f.min <= f.max ? f.min : 1 * f.scale;
    }
    vals.push_back(v);
  }
  std::string out;
  if (!top::encode_fields(form, vals, out)) return top::example_data(form);
  return out;
}

bool same_layout(const top::FormSpec& a, const top::FormSpec& b) {
  if (a.fields.size() != b.fields.size()) return false;
  for (std::size_t i = 0; i < a.fields.size(); ++i)
    if (a.fields[i].kind != b.fields[i].kind || a.fields[i].width != b.fields[i].width)
      return false;
  return a.min_length == b.min_length && a.max_length == b.max_length;
}

json send(const top::CommandSpec& c, char control, const std::string& data) {
  json j{{"command", std::string(c.ident)}, {"control", std::string(1, control)}};
  bool printable = true;
  for (unsigned char ch : data) printable = printable && ch >= 0x20 && ch < 0x7F;
  if (printable) {
    j["data"] = data;
  } else {
    std::string hex;
    char b[3];
    for (unsigned char ch : data) {
      std::snprintf(b, sizeof b, "%02X", static_cast<unsigned>(ch));
      hex += b;
    }
    j["data_hex"] = hex;
  }
  return j;
}

json echo_alts() {
  return json::array({json{{"echo", true}},
                      json{{"echo", true},
                           {"addresses", "any"},
                           {"tolerated", true},
                           {"note", "reply keeps the client's address first (some simulators)"}}});
}

// An answer in the reply layout `reply`; addresses kept in the request's
// order are tolerated.
json reply_alts(const json& reply) {
  return json::array(
      {json{{"reply", reply}}, json{{"reply", reply},
                                    {"addresses", "any"},
                                    {"tolerated", true},
                                    {"note", "reply keeps the client's address first"}}});
}

json reply_checks(const top::FormSpec& resp) {
  json fields = json::object();
  for (const auto& f : resp.fields) {
    json chk = json::object();
    if ((f.kind == FieldKind::enum_hex || f.kind == FieldKind::enum_char) && !f.enums.empty()) {
      json names = json::array();
      for (const auto& e : f.enums) names.push_back(std::string(e.name));
      chk["enum"] = names;
    } else if (f.min <= f.max && f.kind != FieldKind::text && f.kind != FieldKind::raw) {
      chk["min"] = f.min;
      chk["max"] = f.max;
    }
    if (!chk.empty()) fields[std::string(f.name)] = chk;
  }
  return fields;
}

json models_of(const top::CommandSpec& c) {
  json models = json::array();
  for (top::Model m : top::all_models())
    if (c.models & top::model_bit(m)) models.push_back(std::string(top::to_string(m)));
  return models;
}

}  // namespace

json generate_matrix(top::Model model) {
  const Dialect d = top::dialect_of(model);
  const bool sky = d == Dialect::skydroid;
  const std::string dn(top::to_string(d));
  const std::string doc =
      sky ? "SkyDroid TOP protocol V1.1.5 (seeds/000_3e8dc32e1138ca8b.txt)"
          : "Topotek SIP Udp&uart-Protocol V1.1.3 (seeds/001_3ee7043eb5910c28.txt)";
  json m;
  m["$schema"] = "../matrix.schema.json";
  m["format"] = "topconf-matrix-1";
  m["title"] = "Default conformance matrix for " + std::string(top::to_string(model)) +
               " (generated from the TOPKit catalog by `topconf generate`; edit freely)";
  m["model"] = std::string(top::to_string(model));
  m["document"] = doc;
  m["defaults"] = {
      {"timeout_ms", 300}, {"retries", 1}, {"settle_ms", 15}, {"probe_timeout_ms", 500}};
  m["probe"] = sky ? json{{"command", "AWB"}, {"control", "r"}, {"data", "00"}}
                   : json{{"command", "VER"}, {"control", "r"}, {"data", "00"}, {"dst", "G"}};
  json cases = json::array();
  const auto negative_silence = json{{"silence_ms", 60}};
  auto error_alts = [&]() {
    if (!sky) return json::array({negative_silence});
    return json::array({json{{"error", true}},
                        json{{"error", true},
                             {"addresses", "any"},
                             {"tolerated", true},
                             {"note", "ERE without swapped addresses"}},
                        json{{"silence_ms", 60},
                             {"tolerated", true},
                             {"note", "the device ignores the invalid command instead of ERE"}}});
  };
  const std::string ere_section = sky ? "SkyDroid 2.3.2" : "Topotek 2";

  std::vector<std::string> classes_done;
  for (const top::CommandSpec& c : top::commands(d)) {
    if (!c.supports(model) || c.ident == "ERE") continue;
    const std::string id = std::string(c.ident);
    const std::string base = dn + "/" + section_number(c.section) + "/" + id;
    const bool appendix = c.section.find("appendix") != std::string_view::npos;
    const bool destructive = id == "RST" || id == "RTF";
    const std::string level = appendix || destructive ? "may" : "must";
    const std::string cls(1, c.address);
    const json models = models_of(c);
    auto tags = [&](std::initializer_list<const char*> extra) {
      json t = json::array({std::string("class-") + cls, id});
      for (auto e : extra) t.push_back(e);
      if (appendix) t.push_back("appendix");
      if (destructive) t.push_back("destructive");
      return t;
    };
    const top::FormSpec* w = find_form(c, 'w', top::Role::request);
    const top::FormSpec* rq = find_form(c, 'r', top::Role::request);
    const top::FormSpec* rs = find_form(c, 'r', top::Role::response);
    std::string wdata;
    if (w) {
      wdata = top::example_data(*w);
      // Pushes are the stream case's business: switch them off.
      if (top::stream_enabled_by(d, id)) wdata = "00";
      if (!clean_request(d, model, c, 'w', wdata)) w = nullptr;
    }
    // A write with its own reply layout (Topotek REC/CAP: state and file
    // index) is answered in that layout; any other write is echoed.
    const top::FormSpec* wr = nullptr;
    for (const auto& f : c.forms)
      if (f.control == 'w' && f.role == top::Role::response) wr = &f;
    if (w) {
      json expect = echo_alts();
      std::string answer = "echoed with the addresses swapped";
      if (wr) {
        json reply = {{"control", "w"}};
        json f = reply_checks(*wr);
        if (!f.empty()) reply["fields"] = f;
        expect = reply_alts(reply);
        answer = "answered in its reply layout";
      }
      cases.push_back(
          {{"id", base + "/write"},
           {"section", std::string(c.section)},
           {"title", std::string(c.title) + ": a write is " + answer},
           {"level", level},
           {"models", models},
           {"tags", tags({"positive", "write"})},
           {"steps", json::array({{{"send", send(c, 'w', wdata)}, {"expect", expect}}})}});
    }
    std::string rdata;
    if (rq) {
      rdata = top::example_data(*rq);
      if (!clean_request(d, model, c, 'r', rdata)) rq = nullptr;
    }
    if (rq) {
      json reply = {{"control", "r"}};
      if (rs && rs->role == top::Role::response) {
        json f = reply_checks(*rs);
        if (!f.empty()) reply["fields"] = f;
      }
      if (appendix) reply.erase("control");
      cases.push_back({{"id", base + "/read"},
                       {"section", std::string(c.section)},
                       {"title", std::string(c.title) + ": a read is answered with data"},
                       {"level", level},
                       {"models", models},
                       {"tags", tags({"positive", "read"})},
                       {"steps", json::array({{{"send", send(c, 'r', rdata)},
                                               {"expect", reply_alts(reply)}}})}});
    }
    if (w && rq && rs && rs->role == top::Role::response && same_layout(*w, *rs) && !destructive) {
      std::string alt = alternate_data(*w);
      if (!clean_request(d, model, c, 'w', alt)) alt = wdata;
      cases.push_back(
          {{"id", base + "/state"},
           {"section", std::string(c.section)},
           {"title", std::string(c.title) + ": a written value reads back"},
           {"level", level == "must" ? "should" : level},
           {"models", models},
           {"tags", tags({"state"})},
           {"steps",
            json::array({{{"send", send(c, 'w', alt)},
                          {"expect", json::array({json{
                                         {"readback", {{"send", send(c, 'r', rdata)}}}}})}}})}});
    }
    // Negative: wrong length (per command) and a bad checksum (per class).
    const top::FormSpec* any = w ? w : rq;
    const char ctl = w ? 'w' : 'r';
    if (any && any->min_length > 0 && any->max_length < 15) {
      const std::string bad = (w ? wdata : rdata).substr(0, any->min_length - 1);
      cases.push_back(
          {{"id", base + "/wrong-length"},
           {"section", ere_section},
           {"title", std::string(c.title) + ": a frame with a wrong data length is rejected"},
           {"level", "should"},
           {"models", models},
           {"tags", tags({"negative", "wrong-length"})},
           {"steps", json::array({{{"send", send(c, ctl, bad)}, {"expect", error_alts()}}})}});
    }
    if (any && std::find(classes_done.begin(), classes_done.end(), cls) == classes_done.end()) {
      classes_done.push_back(cls);
      top::BuildSpec b;
      b.src = sky ? 'U' : 'P';
      b.dst = c.address;
      b.control = ctl;
      b.ident = c.ident;
      const std::string data = w ? wdata : rdata;
      b.data = data;
      b.header = top::choose_header(d, c.address, data.size());
      std::string f = top::build_frame(b);
      // Corrupt the checksum: add one to its value.
      const std::uint8_t bad_cs =
          static_cast<std::uint8_t>(top::checksum(f.substr(0, f.size() - 2)) + 1);
      char cs[2];
      top::put_hex2(bad_cs, cs);
      f.replace(f.size() - 2, 2, cs, 2);
      if (!sky) f.replace(3, 1, "{client}");
      cases.push_back({{"id", dn + "/frame/bad-checksum/class-" + cls},
                       {"section", sky ? "SkyDroid 2.3" : "Topotek 2"},
                       {"title", "a " + id + " frame with a wrong checksum gets no answer"},
                       {"level", "should"},
                       {"tags", json::array({"negative", "bad-checksum", "class-" + cls})},
                       {"steps", json::array({{{"send", {{"raw", f}}},
                                               {"expect", json::array({negative_silence})}}})}});
    }
  }
  // Unknown identifier.
  cases.push_back(
      {{"id", dn + "/frame/unknown-ident"},
       {"section", ere_section},
       {"title", "an unknown identifier is rejected (ERE on SkyDroid, silence on Topotek)"},
       {"level", "should"},
       {"tags", json::array({"negative", "unknown-ident"})},
       {"steps",
        json::array(
            {{{"send", {{"command", "ZZZ"}, {"control", "r"}, {"data", "00"}, {"dst", "D"}}},
              {"expect", error_alts()}}})}});
  if (sky) {
    // The document's own ERE example, as an exact frame.
    cases.push_back(
        {{"id", "skydroid/2.3.2/ERE/example"},
         {"section", "SkyDroid 2.3.2"},
         {"title", "the invalid-command reply is exactly #TPMU2wERE!!30"},
         {"level", "should"},
         {"tags", json::array({"negative", "exact-frame"})},
         {"steps", json::array({{{"send", {{"raw", "#TPUM2rZZZ00"}}},
                                 {"expect", json::array({json{{"frame", "#TPMU2wERE!!30"}}})}}})}});
  }
  // Streaming: every device stream of the catalog (top/device.hpp): SkyDroid
  // GAA (rate in Hz), Topotek GAA and GIA (on/off, the device's rate).
  for (const top::StreamSpec& st : top::streams()) {
    if (st.dialect != d || st.sender != top::Sender::device) continue;
    const top::CommandSpec* gaa = top::find_command(d, st.request);
    if (!gaa || !gaa->supports(model)) continue;
    const std::string on = st.rate_in_data ? "0A" : "01";
    const double hz = 10;
    const std::string push(st.push);
    cases.push_back(
        {{"id",
          dn + "/" + section_number(gaa->section) + "/" + std::string(gaa->ident) + "/stream"},
         {"section", std::string(gaa->section)},
         {"title", push + " is pushed at the rate " + std::string(gaa->ident) + " asked for"},
         {"level", "must"},
         {"models", models_of(*gaa)},
         {"tags", json::array({"stream", "class-G", std::string(gaa->ident)})},
         {"steps", json::array({
                       {{"send", send(*gaa, 'w', on)}, {"expect", echo_alts()}},
                       {{"expect", json::array({json{{"stream",
                                                      {{"ident", push},
                                                       {"rate_hz", hz},
                                                       {"tolerance", 0.25},
                                                       {"duration_ms", 450}}}}})}},
                       {{"send", send(*gaa, 'w', "00")}, {"expect", echo_alts()}},
                   })}});
  }
  m["cases"] = cases;
  return m;
}

}  // namespace topconf
