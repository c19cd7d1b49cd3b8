#include "conf/generate.hpp"

#include <cstdio>
#include <string>
#include <vector>

#include "top/device.hpp"

namespace topconf {
namespace {

using ojson = nlohmann::ordered_json;
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
  for (const auto& f : c.forms) {
    // The default matrices test the documents: a request form only the
    // field gives (the C13's SLR trigger write) is not theirs.
    if (f.from_field() && f.role != top::Role::response) continue;
    if (f.control == control && (f.role == role || f.role == top::Role::any)) return &f;
  }
  return nullptr;
}

bool clean_request(Dialect d, top::Model m, const top::CommandSpec& c, char control,
                   const std::string& data) {
  top::BuildSpec b;
  b.src = top::client_address(d, top::Link::network);
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

ojson send(const top::CommandSpec& c, char control, const std::string& data) {
  ojson j{{"command", std::string(c.ident)}, {"control", std::string(1, control)}};
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

// A write the document gives no answer (top::write_reply: nothing): its
// silence, or tolerated, an echo the document does not give.
ojson unanswered_alts(const top::CommandSpec& c) {
  const std::string why =
      "the document gives " + std::string(c.ident) + " w no reply form (top::write_reply: nothing)";
  return ojson::array({ojson{{"silence_ms", 60}},
                       ojson{{"echo", true}, {"tolerated", true}, {"note", "an echo: " + why}},
                       ojson{{"echo", true},
                             {"addresses", "any"},
                             {"tolerated", true},
                             {"note", "an echo keeping the client's address first: " + why}}});
}

ojson echo_alts() {
  return ojson::array(
      {ojson{{"echo", true}},
       ojson{{"echo", true},
             {"addresses", "any"},
             {"tolerated", true},
             {"note", "reply keeps the client's address first (some simulators)"}}});
}

// An answer in the reply layout `reply`; addresses kept in the request's
// order are tolerated.
ojson reply_alts(const ojson& reply) {
  return ojson::array(
      {ojson{{"reply", reply}}, ojson{{"reply", reply},
                                      {"addresses", "any"},
                                      {"tolerated", true},
                                      {"note", "reply keeps the client's address first"}}});
}

ojson reply_checks(const top::FormSpec& resp) {
  ojson fields = ojson::object();
  for (const auto& f : resp.fields) {
    ojson chk = ojson::object();
    if ((f.kind == FieldKind::enum_hex || f.kind == FieldKind::enum_char) && !f.enums.empty()) {
      ojson names = ojson::array();
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

ojson models_of(const top::CommandSpec& c) {
  ojson models = ojson::array();
  for (top::Model m : top::all_models())
    if (c.models & top::model_bit(m)) models.push_back(std::string(top::to_string(m)));
  return models;
}

// The matrix of one model, built case by case.
struct Generator {
  top::Model model;
  Dialect d = top::dialect_of(model);
  bool sky = d == Dialect::skydroid;
  std::string dn = std::string(top::to_string(d));
  std::string ere_section = sky ? "SkyDroid 2.3.2" : "Topotek 2";
  ojson negative_silence = ojson{{"silence_ms", 60}};
  ojson cases = ojson::array();
  std::vector<std::string> classes_done;

  ojson error_alts() const {
    if (!sky) return ojson::array({negative_silence});
    return ojson::array({ojson{{"error", true}},
                         ojson{{"error", true},
                               {"addresses", "any"},
                               {"tolerated", true},
                               {"note", "ERE without swapped addresses"}},
                         ojson{{"silence_ms", 60},
                               {"tolerated", true},
                               {"note", "the device ignores the invalid command instead of ERE"}}});
  }

  ojson head() const {
    const std::string doc =
        sky ? "SkyDroid TOP protocol V1.1.5 (seeds/000_3e8dc32e1138ca8b.txt)"
            : "Topotek SIP Udp&uart-Protocol V1.1.3 (seeds/001_3ee7043eb5910c28.txt)";
    ojson m;
    m["$schema"] = "../matrix.schema.json";
    m["format"] = "topconf-matrix-1";
    m["title"] = "Default conformance matrix for " + std::string(top::to_string(model)) +
                 " (generated from the TOPKit catalog by `topconf generate`; edit freely)";
    m["model"] = std::string(top::to_string(model));
    m["document"] = doc;
    m["defaults"] = {
        {"timeout_ms", 300}, {"retries", 1}, {"settle_ms", 15}, {"probe_timeout_ms", 500}};
    // No "probe": the runner tries the catalog's liveness probes for the
    // model (top/probe.hpp), so a device that answers another one is reached.
    return m;
  }

  // What the cases of one command share.
  struct Command {
    const top::CommandSpec& c;
    std::string id, base, level, cls;
    bool appendix = false, destructive = false;
    ojson models;
    const top::FormSpec *w = nullptr, *rq = nullptr, *rs = nullptr;
    std::string wdata, rdata;
    ojson tags(std::initializer_list<const char*> extra) const {
      ojson t = ojson::array({std::string("class-") + cls, id});
      for (auto e : extra) t.push_back(e);
      if (appendix) t.push_back("appendix");
      if (destructive) t.push_back("destructive");
      return t;
    }
    ojson head(const std::string& suffix, const std::string& title, const std::string& lvl,
               ojson tag_list) const {
      return {{"id", base + suffix},
              {"section", std::string(c.section)},
              {"title", std::string(c.title) + title},
              {"level", lvl},
              {"models", models},
              {"tags", std::move(tag_list)}};
    }
  };

  Command command_of(const top::CommandSpec& c) const {
    Command k{c};
    k.id = std::string(c.ident);
    k.base = dn + "/" + section_number(c.section) + "/" + k.id;
    k.appendix = c.section.find("appendix") != std::string_view::npos;
    k.destructive = k.id == "RST" || k.id == "RTF";
    k.level = k.appendix || k.destructive ? "may" : "must";
    k.cls = std::string(1, c.address);
    k.models = models_of(c);
    k.w = find_form(c, 'w', top::Role::request);
    k.rq = find_form(c, 'r', top::Role::request);
    k.rs = find_form(c, 'r', top::Role::response);
    if (k.w) {
      k.wdata = top::example_data(*k.w);
      // Pushes are the stream case's business: switch them off.
      if (top::stream_enabled_by(d, k.id)) k.wdata = "00";
      if (!clean_request(d, model, c, 'w', k.wdata)) k.w = nullptr;
    }
    if (k.rq) {
      k.rdata = top::example_data(*k.rq);
      if (!clean_request(d, model, c, 'r', k.rdata)) k.rq = nullptr;
    }
    return k;
  }

  // A state case's read: one whose reply has the write's layout.
  bool readable(const Command& k) const {
    return k.w && k.rq && k.rs && k.rs->role == top::Role::response && same_layout(*k.w, *k.rs) &&
           !k.destructive;
  }

  void positive(const Command& k) {
    const top::CommandSpec& c = k.c;
    // A write with its own reply layout (Topotek REC/CAP: state and file
    // index) is answered in that layout; one the document gives no answer
    // (top::write_reply: a Topotek set/control write) is checked by its
    // silence, or by reading it back where a read can; any other write is
    // echoed.
    const top::FormSpec* wr = nullptr;
    for (const auto& f : c.forms)
      if (f.control == 'w' && f.role == top::Role::response && !f.from_field()) wr = &f;
    if (k.w && top::write_reply(c) == top::WriteReply::nothing) {
      ojson cs = k.head("/write",
                        readable(k) ? ": a write takes effect without an answer (read back)"
                                    : ": a write is taken without an answer",
                        k.level, k.tags({"positive", "write"}));
      ojson step = {{"send", send(c, 'w', k.wdata)}};
      step["expect"] = readable(k)
                           ? ojson::array({ojson{{"readback", {{"send", send(c, 'r', k.rdata)}}}}})
                           : unanswered_alts(c);
      cs["steps"] = ojson::array({step});
      cases.push_back(std::move(cs));
    } else if (k.w) {
      ojson expect = echo_alts();
      std::string answer = "echoed with the addresses swapped";
      if (wr) {
        ojson reply = {{"control", "w"}};
        ojson f = reply_checks(*wr);
        if (!f.empty()) reply["fields"] = f;
        expect = reply_alts(reply);
        answer = "answered in its reply layout";
      }
      field_write_replies(k, expect);
      ojson cs = k.head("/write", ": a write is " + answer, k.level, k.tags({"positive", "write"}));
      cs["steps"] = ojson::array({{{"send", send(c, 'w', k.wdata)}, {"expect", expect}}});
      cases.push_back(std::move(cs));
    }
    if (k.rq) {
      ojson reply = {{"control", "r"}};
      if (k.rs && k.rs->role == top::Role::response) {
        ojson f = reply_checks(*k.rs);
        if (!f.empty()) reply["fields"] = f;
      }
      if (k.appendix) reply.erase("control");
      ojson cs =
          k.head("/read", ": a read is answered with data", k.level, k.tags({"positive", "read"}));
      cs["steps"] =
          ojson::array({{{"send", send(c, 'r', k.rdata)}, {"expect", reply_alts(reply)}}});
      cases.push_back(std::move(cs));
    }
    if (readable(k)) {
      std::string alt = alternate_data(*k.w);
      if (!clean_request(d, model, c, 'w', alt)) alt = k.wdata;
      ojson cs = k.head("/state", ": a written value reads back",
                        k.level == "must" ? "should" : k.level, k.tags({"state"}));
      cs["steps"] = ojson::array(
          {{{"send", send(c, 'w', alt)},
            {"expect", ojson::array({ojson{{"readback", {{"send", send(c, 'r', k.rdata)}}}}})}}});
      cases.push_back(std::move(cs));
    }
  }

  // The answers to a write that only the field gives (top/catalog.hpp
  // from_field), after the document's: its echo where the field's form has
  // the request's layout (a real unit echoes the LAT/LON writes), else a
  // reply in the field's layout (LRF's 5 digits). topconf reports a match
  // as the field's form, with its evidence.
  void field_write_replies(const Command& k, ojson& expect) const {
    for (const auto& f : k.c.forms) {
      if (f.control != 'w' || f.role != top::Role::response || !f.from_field()) continue;
      ojson alt = ojson{{"echo", true}};
      if (!same_layout(*k.w, f)) {
        ojson reply = {{"control", "w"}};
        ojson checks = reply_checks(f);
        if (!checks.empty()) reply["fields"] = checks;
        alt = ojson{{"reply", reply}};
      }
      alt["note"] = "the field's answer: " + std::string(f.evidence);
      expect.push_back(std::move(alt));
    }
  }

  // Negative: wrong length (per command) and a bad checksum (per class).
  void negative(const Command& k) {
    const top::CommandSpec& c = k.c;
    const top::FormSpec* any = k.w ? k.w : k.rq;
    const char ctl = k.w ? 'w' : 'r';
    if (any && any->min_length > 0 && any->max_length < 15) {
      const std::string bad = (k.w ? k.wdata : k.rdata).substr(0, any->min_length - 1);
      ojson cs = k.head("/wrong-length", ": a frame with a wrong data length is rejected", "should",
                        k.tags({"negative", "wrong-length"}));
      cs["section"] = ere_section;
      cs["steps"] = ojson::array({{{"send", send(c, ctl, bad)}, {"expect", error_alts()}}});
      cases.push_back(std::move(cs));
    }
    if (!any || std::find(classes_done.begin(), classes_done.end(), k.cls) != classes_done.end())
      return;
    classes_done.push_back(k.cls);
    top::BuildSpec b;
    b.src = top::client_address(d, top::Link::network);
    b.dst = c.address;
    b.control = ctl;
    b.ident = c.ident;
    const std::string data = k.w ? k.wdata : k.rdata;
    b.data = data;
    b.header = top::choose_header(d, c.address, data.size());
    // A wrong checksum: one more than the sum.
    b.omit_checksum = true;
    b.checksum = static_cast<std::uint8_t>(top::checksum(top::build_frame(b)) + 1);
    b.omit_checksum = false;
    std::string f = top::build_frame(b);
    if (!sky) f.replace(3, 1, "{client}");
    cases.push_back({{"id", dn + "/frame/bad-checksum/class-" + k.cls},
                     {"section", sky ? "SkyDroid 2.3" : "Topotek 2"},
                     {"title", "a " + k.id + " frame with a wrong checksum gets no answer"},
                     {"level", "should"},
                     {"tags", ojson::array({"negative", "bad-checksum", "class-" + k.cls})},
                     {"steps", ojson::array({{{"send", {{"raw", f}}},
                                              {"expect", ojson::array({negative_silence})}}})}});
  }

  void frame_cases() {
    // Unknown identifier.
    cases.push_back(
        {{"id", dn + "/frame/unknown-ident"},
         {"section", ere_section},
         {"title", "an unknown identifier is rejected (ERE on SkyDroid, silence on Topotek)"},
         {"level", "should"},
         {"tags", ojson::array({"negative", "unknown-ident"})},
         {"steps",
          ojson::array(
              {{{"send", {{"command", "ZZZ"}, {"control", "r"}, {"data", "00"}, {"dst", "D"}}},
                {"expect", error_alts()}}})}});
    if (!sky) return;
    // The document's own ERE example, as an exact frame.
    cases.push_back(
        {{"id", "skydroid/2.3.2/ERE/example"},
         {"section", "SkyDroid 2.3.2"},
         {"title", "the invalid-command reply is exactly #TPMU2wERE!!30"},
         {"level", "should"},
         {"tags", ojson::array({"negative", "exact-frame"})},
         {"steps",
          ojson::array({{{"send", {{"raw", "#TPUM2rZZZ00"}}},
                         {"expect", ojson::array({ojson{{"frame", "#TPMU2wERE!!30"}}})}}})}});
  }

  // Streaming: every device stream of the catalog (top/device.hpp): SkyDroid
  // GAA (rate in Hz), Topotek GAA and GIA (on/off, the device's rate).
  void stream_cases() {
    for (const top::StreamSpec& st : top::streams()) {
      // The document's streams (a field stream: top/device.hpp, from_field).
      if (st.dialect != d || st.sender != top::Sender::device || st.from_field()) continue;
      const top::CommandSpec* gaa = top::find_command(d, st.request);
      if (!gaa || !gaa->supports(model)) continue;
      const std::string on = st.rate_in_data ? "0A" : "01";
      const double hz = 10;
      const std::string push(st.push);
      auto stream_of = [&](std::string_view ident) {
        return ojson{{"stream",
                      {{"ident", std::string(ident)},
                       {"rate_hz", hz},
                       {"tolerance", top::stream_rate_tolerance},
                       {"duration_ms", 450}}}};
      };
      ojson pushes = ojson::array({stream_of(st.push)});
      // The field's stream of the same switch (Topotek GIA 01 pushing GIA
      // frames), reported as the field's form.
      const top::StreamSpec* fs = top::stream_enabled_by(d, st.request, top::Profile::field);
      if (fs && fs->push != st.push) {
        ojson alt = stream_of(fs->push);
        alt["note"] = "the field's stream: " + std::string(fs->evidence);
        pushes.push_back(std::move(alt));
      }
      // The switch's answer: its echo, or none where the document gives
      // it none (top::write_reply); then the pushes are the answer.
      const bool echoed = top::write_reply(*gaa) != top::WriteReply::nothing;
      ojson steps = echoed
                        ? ojson::array({
                              {{"send", send(*gaa, 'w', on)}, {"expect", echo_alts()}},
                              {{"expect", pushes}},
                              {{"send", send(*gaa, 'w', "00")}, {"expect", echo_alts()}},
                          })
                        : ojson::array({
                              {{"send", send(*gaa, 'w', on)}, {"expect", pushes}},
                              {{"send", send(*gaa, 'w', "00")}, {"expect", unanswered_alts(*gaa)}},
                          });
      cases.push_back(
          {{"id",
            dn + "/" + section_number(gaa->section) + "/" + std::string(gaa->ident) + "/stream"},
           {"section", std::string(gaa->section)},
           {"title", push + " is pushed at the rate " + std::string(gaa->ident) + " asked for"},
           {"level", "must"},
           {"models", models_of(*gaa)},
           {"tags", ojson::array({"stream", "class-G", std::string(gaa->ident)})},
           {"steps", std::move(steps)}});
    }
  }
};

}  // namespace

ojson generate_matrix(top::Model model) {
  Generator g{model};
  ojson m = g.head();
  for (const top::CommandSpec& c : top::commands(g.d)) {
    // The default matrices test the documents; the field's commands (TRC,
    // LOC: top/catalog.hpp, from_field) are not theirs.
    if (!c.supports(model) || top::is_error_reply(c.ident) || c.from_field()) continue;
    const Generator::Command k = g.command_of(c);
    g.positive(k);
    g.negative(k);
  }
  g.frame_cases();
  g.stream_cases();
  m["cases"] = g.cases;
  return m;
}

}  // namespace topconf
