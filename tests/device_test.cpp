// The device rules of top/device.hpp that topsim, topconf, the fuzzers and
// topdump all ask: which link answers which source, which findings make a
// device reject a request, the ERE reply, the timing limits.
#include "top/device.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "top/top.hpp"

using namespace top;

namespace {

Decoded decode_text(const std::string& text, Model model) {
  const ParseResult r = parse_exact(with_checksum(text));
  EXPECT_EQ(r.status, ParseStatus::frame) << text;
  DecodeOptions o;
  o.dialect = dialect_of(model);
  o.model = model;
  return decode(r.frame, o);
}

}  // namespace

TEST(DeviceRules, ClientAddressIsTheLinksOnTopotekAndUOnSkydroid) {
  EXPECT_EQ(client_address(Dialect::topotek, Link::network), 'P');
  EXPECT_EQ(client_address(Dialect::topotek, Link::uart), 'U');
  EXPECT_EQ(client_address(Dialect::skydroid, Link::network), 'U');
  EXPECT_EQ(client_address(Dialect::skydroid, Link::uart), 'U');
}

// Topotek 2: the source byte names the interface; the trait is a document
// rule, so it holds under both profiles.
TEST(DeviceRules, TopotekAnswersOnlyTheLinkTheSourceNames) {
  for (Profile p : {Profile::field, Profile::document}) {
    EXPECT_TRUE(answers_source(Model::sip, p, Link::network, 'P'));
    EXPECT_FALSE(answers_source(Model::sip, p, Link::network, 'U'));
    EXPECT_TRUE(answers_source(Model::sip, p, Link::uart, 'U'));
    EXPECT_FALSE(answers_source(Model::sip, p, Link::uart, 'P'));
  }
  ASSERT_NE(find_trait(TraitKind::link_by_source, Model::sip, Profile::document), nullptr);
  // A capture's device of unknown model: the dialect's rule.
  EXPECT_FALSE(answers_source(Dialect::topotek, Profile::field, Link::network, 'U'));
  EXPECT_TRUE(answers_source(Dialect::topotek, Profile::field, Link::uart, 'U'));
  EXPECT_TRUE(answers_source(Dialect::skydroid, Profile::field, Link::network, 'P'));
}

TEST(DeviceRules, SkydroidAnswersEverySource) {
  for (Model m : {Model::c10, Model::c12, Model::c13, Model::c20})
    for (Link l : {Link::network, Link::uart})
      for (char src : {'U', 'P'}) EXPECT_TRUE(answers_source(m, Profile::field, l, src));
}

// answers_other_query is exactly "answers_query holds for some other
// request": the session asks it before scanning its pending reads, so a
// false where a form answers another read would lose a pairing.
TEST(DeviceRules, AnswersOtherQueryIsTheRecordedCrossAnswers) {
  EXPECT_TRUE(answers_query(Dialect::topotek, "GIC", "GIA"));  // a real SIP's
  EXPECT_TRUE(answers_other_query(Dialect::topotek, "GIA"));
  EXPECT_FALSE(answers_other_query(Dialect::skydroid, "GIA"));
  EXPECT_FALSE(answers_other_query(Dialect::topotek, "GIC"));
  EXPECT_FALSE(answers_other_query(Dialect::skydroid, "GAC"));
  // every identifier a form names, as a request and as a reply
  std::vector<std::string_view> idents;
  for (const DeviceForm& f : device_forms()) {
    idents.push_back(f.ident);
    if (!f.answers.empty()) idents.push_back(f.answers);
  }
  for (Dialect d : {Dialect::skydroid, Dialect::topotek})
    for (std::string_view reply : idents) {
      bool other = false;
      for (std::string_view request : idents)
        other = other || (request != reply && answers_query(d, request, reply));
      EXPECT_EQ(answers_other_query(d, reply), other) << reply;
    }
}

// A write the device echoes must have a form its echo fits: LOC's only
// form was a request's, so topdump noted unswapped-addresses on the echo it
// expects (an outside capture's healthy tracking: "laid out as a request
// but addressed D to P").
TEST(DeviceRules, AnEchoedWriteHasAFormItsEchoFits) {
  for (const top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek})
    for (const top::CommandSpec& c : top::commands(d)) {
      if (top::write_reply(c) != top::WriteReply::echo) continue;
      bool writes = false, echo = false;
      for (const top::FormSpec& f : c.forms)
        if (f.control == 'w') {
          writes = true;
          echo |= f.role != top::Role::request;
        }
      EXPECT_TRUE(!writes || echo) << c.ident;
    }
}

TEST(DeviceRules, RejectionOfACleanCommandIsNone) {
  EXPECT_EQ(rejection(decode_text("#TPUG2wGAA0A", Model::c12), Model::c12), Rejection::none);
  EXPECT_EQ(rejection(Decoded{}, Model::c12), Rejection::none);
}

TEST(DeviceRules, UnknownIdentifierIsUnsupported) {
  const Decoded d = decode_text("#TPUG2wQQQ01", Model::c12);
  EXPECT_EQ(rejection(d, Model::c12), Rejection::unsupported);
}

TEST(DeviceRules, WrongLengthOrRangeIsInvalid) {
  EXPECT_EQ(rejection(decode_text("#TPUG4wGAA0A0B", Model::c12), Model::c12), Rejection::invalid);
  EXPECT_EQ(rejection(decode_text("#tpUG6wGAY7FFF10", Model::c12), Model::c12), Rejection::invalid);
}

// C13 PTZ 0E: the document lists PTZ for other models, field evidence says
// the C13 takes it. The decoder makes that a warning; the field profile
// takes it, the document profile (no field evidence) refuses it.
TEST(DeviceRules, FieldEvidenceLiftsUnsupportedOnModel) {
  const Decoded d = decode_text("#TPUG2wPTZ0E", Model::c13);
  ASSERT_FALSE(d.findings.empty());
  EXPECT_EQ(rejection(d, Model::c13, true), Rejection::none);
  EXPECT_EQ(rejection(d, Model::c13, false), Rejection::unsupported);
  // The evidence names the values it saw working: PTZ 00 (stop) is not one
  // of them, so the C13 refuses it whatever the decoder's severity.
  EXPECT_EQ(rejection(decode_text("#TPUG2wPTZ00", Model::c13), Model::c13, true),
            Rejection::unsupported);
  EXPECT_EQ(rejection(decode_text("#TPUG2wPTZ09", Model::c13), Model::c13, true),
            Rejection::unsupported);
}

// ---- The field (issue 28; docs/sources/ardupilot.md) ----

// ArduPilot's SkyDroid driver drives the C13 with GAA, GSY, GSP and PTZ
// 05/06/07 (PR #34155: SkyDroid confirmed the C11/C13 commands are the
// same), and a C13 station reads GAC: the field profile takes them, the
// document profile keeps the document's support lines.
TEST(DeviceField, C13TakesTheAttitudeAndGimbalCommandsOfTheField) {
  for (const char* text : {"#TPUG2wGAA32", "#TPUGCrGAC000000000000", "#TPUG2wGSY0A", "#TPUG2wGSPF6",
                           "#TPUG2wPTZ05", "#TPUG2wPTZ06", "#TPUG2wPTZ07"}) {
    const Decoded d = decode_text(text, Model::c13);
    const Finding* u = nullptr;
    for (const Finding& x : d.findings)
      if (x.code == FindingCode::unsupported_on_model) u = &x;
    ASSERT_NE(u, nullptr) << text;
    EXPECT_EQ(u->severity, Severity::info) << text;  // healthy C13 traffic: no warning
    EXPECT_FALSE(u->quirk.empty()) << text;
    EXPECT_EQ(rejection(d, Model::c13, true), Rejection::none) << text;
    EXPECT_EQ(rejection(d, Model::c13, false), Rejection::unsupported) << text;
  }
  const FieldSupport* gsy = field_supported(Dialect::skydroid, Model::c13, "GSY", 0x0A);
  ASSERT_NE(gsy, nullptr);
  EXPECT_NE(gsy->evidence.find("PR #34155"), std::string_view::npos);
  EXPECT_EQ(field_supported(Dialect::skydroid, Model::c12, "GSY", 0x0A), nullptr);
  // GAM is not in the field evidence for the C13.
  EXPECT_EQ(field_supported(Dialect::skydroid, Model::c13, "GAM", std::nullopt), nullptr);
}

// The field's commands and forms: taken under the field profile, refused
// under the document's.
TEST(DeviceField, DocumentProfileRefusesTheFieldsCommandsAndForms) {
  const Decoded trc = decode_text("#TPUD2rTRC00", Model::sip);
  EXPECT_TRUE(trc.findings.empty());
  EXPECT_EQ(rejection(trc, Model::sip, true), Rejection::none);
  EXPECT_EQ(rejection(trc, Model::sip, false), Rejection::unsupported);
  const Decoded pa2 = decode_text("#TPUG2rPA200", Model::sip);
  EXPECT_EQ(rejection(pa2, Model::sip, false), Rejection::unsupported);
  // A 12-char GIA is a field form of a document's command.
  const Decoded reply = decode_text("#tpGUCrGIA00000BB80000", Model::sip);
  ASSERT_NE(reply.form, nullptr);
  EXPECT_TRUE(reply.form->from_field());
  EXPECT_EQ(rejection(reply, Model::sip, true), Rejection::none);
  EXPECT_EQ(rejection(reply, Model::sip, false), Rejection::invalid);
  // The document's GIA switch stays clean under both.
  const Decoded on = decode_text("#TPUG2wGIA01", Model::sip);
  EXPECT_EQ(rejection(on, Model::sip, false), Rejection::none);
}

// GIA 01: the document pushes GIC (Topotek 4.3.6), the field GIA frames
// (ArduPilot's driver, a real SIP). Without a profile the document's
// stream answers stream_enabled_by(), and a reader of traffic takes both
// GIC and GIA as pushes.
TEST(DeviceField, GiaEnablePushesGiaUnderTheFieldProfile) {
  const StreamSpec* doc = stream_enabled_by(Dialect::topotek, "GIA");
  ASSERT_NE(doc, nullptr);
  EXPECT_EQ(doc->push, "GIC");
  EXPECT_FALSE(doc->from_field());
  EXPECT_EQ(stream_enabled_by(Dialect::topotek, "GIA", Profile::document), doc);
  const StreamSpec* field = stream_enabled_by(Dialect::topotek, "GIA", Profile::field);
  ASSERT_NE(field, nullptr);
  EXPECT_EQ(field->push, "GIA");
  EXPECT_EQ(field->request, "GIA");
  EXPECT_TRUE(field->from_field());
  EXPECT_EQ(field->sender, Sender::device);
  EXPECT_NE(field->evidence.find("AP_Mount_Topotek.h @ 02246a61"), std::string_view::npos);
  EXPECT_NE(field->evidence.find("@ 3d293ff8"), std::string_view::npos);
  // GAA has no field stream: the field profile gives the document's.
  EXPECT_EQ(stream_enabled_by(Dialect::topotek, "GAA", Profile::field)->push, "GAC");
  // Which frames are pushes.
  EXPECT_EQ(stream_of(Dialect::topotek, "GIC"), doc);
  EXPECT_EQ(stream_of(Dialect::topotek, "GIA"), field);
  EXPECT_EQ(stream_of(Dialect::topotek, "GIA", Profile::document), nullptr);
  EXPECT_EQ(stream_of(Dialect::topotek, "GIA", Profile::field), field);
  // The tracking box: pushed after LOC, a field stream only.
  const StreamSpec* oft = stream_of(Dialect::topotek, "OFT");
  ASSERT_NE(oft, nullptr);
  EXPECT_EQ(oft->request, "LOC");
  EXPECT_EQ(stream_enabled_by(Dialect::topotek, "LOC"), nullptr);
  EXPECT_EQ(stream_enabled_by(Dialect::topotek, "LOC", Profile::field), oft);
  // The stream table lists every field stream after the document's of the
  // same request.
  bool field_seen = false;
  for (const StreamSpec& s : streams()) {
    if (s.request == "GIA" && s.dialect == Dialect::topotek) {
      if (s.from_field())
        field_seen = true;
      else
        EXPECT_FALSE(field_seen);
    }
  }
  // A GIA write gets no reply (Topotek 2: w is set/control; the stream's
  // frames are what it turns on), nor does any Topotek write the document
  // gives no reply form; REC answers with its file index, and every
  // SkyDroid write is echoed (SkyDroid 2.3.1).
  const CommandSpec* gia = find_command(Dialect::topotek, "GIA");
  ASSERT_NE(gia, nullptr);
  EXPECT_EQ(write_reply(*gia), WriteReply::nothing);
  EXPECT_EQ(write_reply(*find_command(Dialect::topotek, "PTZ")), WriteReply::nothing);
  EXPECT_EQ(write_reply(*find_command(Dialect::topotek, "REC")), WriteReply::file_index);
  EXPECT_EQ(write_reply(*find_command(Dialect::skydroid, "PTZ")), WriteReply::echo);
}

TEST(DeviceField, FormsAndTraitsOfTheFieldNameTheirSources) {
  // #tp kept on a 2-char reply (issue 28: #tpPG2rGMS0089 -> #tpGP2rGMS018A).
  const DeviceForm gms = device_form(Model::sip, "GMS", 'r', Sent::reply, 2, Profile::field);
  EXPECT_EQ(gms.header, Header::variable);
  EXPECT_EQ(gms.source, Source::field);
  EXPECT_NE(gms.evidence.find("#tpGP2rGMS018A"), std::string_view::npos);
  EXPECT_EQ(device_form(Model::sip, "GMS", 'r', Sent::reply, 2, Profile::document).header,
            Header::fixed);
  const Trait* keep = find_trait(TraitKind::keeps_request_header, Model::sip, Profile::field);
  ASSERT_NE(keep, nullptr);
  EXPECT_EQ(find_trait(TraitKind::keeps_request_header, Model::sip, Profile::document), nullptr);
  // The GIA reply to a GIC query.
  EXPECT_EQ(device_form(Model::sip, "GIA", 'r', Sent::reply, 12, Profile::field).source,
            Source::field);
  // C13 GSY sign: per identifier, field only.
  const Trait* yaw = find_trait(TraitKind::yaw_inverted, Model::c13, Profile::field);
  ASSERT_NE(yaw, nullptr);
  EXPECT_EQ(yaw->idents, "GSY");
  EXPECT_NE(yaw->evidence.find("custom-GCS"), std::string_view::npos);
  EXPECT_EQ(find_trait(TraitKind::yaw_inverted, Model::c13, Profile::document), nullptr);
  // The C12 pitch trait stays, contested: shown with the sources against,
  // never applied by a profile (the default serves the autopilot).
  EXPECT_EQ(find_trait(TraitKind::pitch_inverted, Model::c12, Profile::field), nullptr);
  const Trait* pitch = find_trait(TraitKind::pitch_inverted, Model::c12, Profile::field, true);
  ASSERT_NE(pitch, nullptr);
  EXPECT_TRUE(pitch->contested);
  EXPECT_TRUE(pitch->names("GAM"));
  EXPECT_FALSE(pitch->names("GSP"));
  // The C12 yaw trait: GSY (the driver's reading) and the GAY/GAM clients'.
  const Trait* yaw12 = find_trait(TraitKind::yaw_inverted, Model::c12, Profile::field);
  ASSERT_NE(yaw12, nullptr);
  EXPECT_TRUE(yaw12->names("GSY"));
  EXPECT_TRUE(yaw12->names("GAM"));
  EXPECT_FALSE(yaw12->names("GA"));
  EXPECT_FALSE(yaw12->names("PTZ"));
  EXPECT_NE(pitch->evidence.find("Against"), std::string_view::npos);
  EXPECT_NE(pitch->evidence.find("log114/PTZControl"), std::string_view::npos);
  // The C10 Pro tool's double-checksum frame.
  const Trait* dbl = find_trait(TraitKind::double_checksum, Model::c10pro, Profile::field);
  ASSERT_NE(dbl, nullptr);
  EXPECT_NE(dbl->evidence.find("#TPUG2wPTZ056FEB"), std::string_view::npos);
  EXPECT_EQ(to_string(TraitKind::double_checksum), "double-checksum");
  EXPECT_EQ(to_string(TraitKind::keeps_request_header), "keeps-request-header");
  // Lengths that count bytes: the C12 palette and a C14 Pro's range.
  const ParseResult img = parse_exact("#TPDU1rIMG0141");
  ASSERT_EQ(img.status, ParseStatus::frame);
  const DeviceForm* f = recorded_form(Dialect::skydroid, Model::c12, img.frame, Sent::reply);
  ASSERT_NE(f, nullptr);
  EXPECT_TRUE(f->length_in_bytes);
  const ParseResult slr = parse_exact("#TPDU2rSLR0018BE");
  ASSERT_EQ(slr.status, ParseStatus::frame);
  EXPECT_EQ(slr.frame.data(), "0018");
  const DeviceForm* s = recorded_form(Dialect::skydroid, Model::unknown, slr.frame, Sent::reply);
  ASSERT_NE(s, nullptr);
  EXPECT_TRUE(s->length_in_bytes);
  EXPECT_EQ(s->models, 0);  // a C14 Pro: no model of the catalog
}

// Issue 28's C13 station notes are recorded with their source, and stay out
// of the rules: UDP 9003 remains the Topotek device port, 19853 no TOP port.
TEST(DeviceField, C13StationNotesAreRecordedNotModelled) {
  bool gac = false, ports = false;
  for (const FieldNote& n : field_notes()) {
    EXPECT_FALSE(n.note.empty());
    EXPECT_FALSE(n.evidence.empty()) << n.note;
    EXPECT_NE(n.models, 0) << n.note;
    const bool c13 = n.dialect == Dialect::skydroid && (n.models & model_bit(Model::c13));
    gac |= c13 && n.ident == "GAC" && n.note.find("0.0") != std::string_view::npos &&
           n.evidence.find("custom-GCS") != std::string_view::npos;
    ports |= c13 && n.note.find("9003") != std::string_view::npos &&
             n.note.find("19853") != std::string_view::npos &&
             n.evidence.find("_ZOOM_EXTRA_PORTS") != std::string_view::npos;
  }
  EXPECT_TRUE(gac);
  EXPECT_TRUE(ports);
  EXPECT_EQ(dialect_from_port(9003), Dialect::topotek);
  EXPECT_EQ(port_role(9003), PortRole::device);
  EXPECT_FALSE(is_top_port(19853));
}

// A device frame of a recorded form decodes as the device sent it: the C12
// palette's tp-length becomes info naming the evidence.
TEST(DeviceField, LengthInBytesReplyDecodesWithItsEvidence) {
  const ParseResult r = parse_exact("#TPDU1rIMG0141");
  ASSERT_EQ(r.status, ParseStatus::frame);
  DecodeOptions o;
  o.model = Model::c12;
  o.role = Role::response;
  const Decoded d = decode(r.frame, o);
  ASSERT_NE(d.form, nullptr);
  for (const Finding& x : d.findings) {
    EXPECT_NE(x.severity, Severity::error);
    if (x.code == FindingCode::tp_length) {
      EXPECT_EQ(x.severity, Severity::info);
      EXPECT_NE(x.quirk.find("log114"), std::string_view::npos);
    }
  }
}

TEST(DeviceRules, UnsupportedWinsOverInvalid) {
  Decoded d;
  d.findings = {make_finding(FindingCode::data_length, 0, ""),
                make_finding(FindingCode::unknown_ident, 0, "")};
  EXPECT_EQ(rejection(d, Model::c12), Rejection::unsupported);
  d.findings.pop_back();
  EXPECT_EQ(rejection(d, Model::c12), Rejection::invalid);
  EXPECT_TRUE(rejects(FindingCode::bad_field));
  EXPECT_FALSE(rejects(FindingCode::bad_checksum));
  EXPECT_FALSE(rejects(FindingCode::lowercase_hex));
}

// SkyDroid 2.3.2's example: a rejected request to the lens is answered
// #TPMU2wERE!!30, addresses swapped; Topotek documents no such reply.
TEST(DeviceRules, ErrorReplyIsTheDocumentsExample) {
  const ParseResult r = parse_exact(with_checksum("#TPUM2wZZZ01"));
  ASSERT_EQ(r.status, ParseStatus::frame);
  const std::string ere = build_frame(error_reply(r.frame));
  EXPECT_EQ(ere, "#TPMU2wERE!!30");
  const ParseResult back = parse_exact(ere);
  ASSERT_EQ(back.status, ParseStatus::frame);
  EXPECT_TRUE(is_error_reply(back.frame));
  EXPECT_FALSE(is_error_reply(r.frame));
  EXPECT_TRUE(answers_error_reply(Dialect::skydroid));
  EXPECT_FALSE(answers_error_reply(Dialect::topotek));
}

TEST(DeviceRules, SpeedHoldIsTheTraitsValueElseTheDefault) {
  const Trait* t = find_trait(TraitKind::speed_refresh, Model::c12, Profile::field);
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(speed_hold_ms(Model::c12, Profile::field), t->value);
  // The trait is field evidence: the document profile has none.
  EXPECT_EQ(find_trait(TraitKind::speed_refresh, Model::c12, Profile::document), nullptr);
  EXPECT_EQ(speed_hold_ms(Model::c12, Profile::document), default_speed_hold_ms);
  EXPECT_EQ(find_trait(TraitKind::speed_refresh, Model::sip, Profile::field), nullptr);
  EXPECT_EQ(speed_hold_ms(Model::sip, Profile::field), default_speed_hold_ms);
}

TEST(DeviceRules, NamesOfTheRuleEnums) {
  EXPECT_EQ(to_string(Link::network), "network");
  EXPECT_EQ(to_string(Link::uart), "uart");
  EXPECT_EQ(to_string(Rejection::invalid), "invalid");
}
