// The field's forms of the catalog (issue 28; docs/sources/ardupilot.md),
// decoded from frames real units, ArduPilot's drivers or stations sent.
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "test_util.hpp"
#include "top/decode.hpp"

using namespace top;
using toptest::dec;
using toptest::field;

// ---- The field's forms (issue 28; docs/sources/ardupilot.md): each frame
// is one a real unit, ArduPilot's drivers or a station was seen to send.

namespace {

// The codes of the frame's findings.
std::vector<FindingCode> codes(const Decoded& d) {
  std::vector<FindingCode> v;
  for (const Finding& f : d.findings) v.push_back(f.code);
  return v;
}

// Decoded as a reply of `ident` with no finding.
::testing::AssertionResult clean_reply(const Decoded& d, std::string_view ident) {
  if (!d.command || d.command->ident != ident)
    return ::testing::AssertionFailure() << "not " << ident << ": " << d.summary();
  if (d.role != Role::response) return ::testing::AssertionFailure() << "not a reply";
  if (!codes(d).empty()) return ::testing::AssertionFailure() << "findings: " << d.summary();
  return ::testing::AssertionSuccess();
}

std::string from_hex(std::string_view hex) {
  std::string out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    out += static_cast<char>(std::stoi(std::string(hex.substr(i, 2)), nullptr, 16));
  return out;
}

}  // namespace

// A real SIP answers the GIC query with a 12-char GIA (issue 28 log);
// ArduPilot's driver reads yaw, pitch (down positive), roll in 0.01 deg.
TEST(DecodeField, GiaAttitudeFrame) {
  const Decoded d = dec("#tpGUCrGIA00000BB8000095", Dialect::topotek, Model::sip);
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "GIA");
  ASSERT_NE(d.form, nullptr);
  EXPECT_TRUE(d.form->from_field());
  EXPECT_EQ(d.role, Role::response);
  EXPECT_TRUE(codes(d).empty()) << d.summary();
  EXPECT_DOUBLE_EQ(field(d, "yaw").value, 0.0);
  EXPECT_DOUBLE_EQ(field(d, "pitch").value, 30.0);  // 30 deg down on the wire
  EXPECT_DOUBLE_EQ(field(d, "roll").value, 0.0);
  // The document's switch is still the document's form.
  const Decoded on = dec("#TPUG2wGIA013E", Dialect::topotek, Model::sip);
  ASSERT_NE(on.form, nullptr);
  EXPECT_FALSE(on.form->from_field());
  EXPECT_EQ(field(on, "state").enum_name, "enable");
  // A negative yaw: FF38 = -2.00 deg.
  const Decoded neg = dec(with_checksum("#tpGPCrGIAFF38000000C8"), Dialect::topotek);
  EXPECT_DOUBLE_EQ(field(neg, "yaw").value, -2.0);
  EXPECT_DOUBLE_EQ(field(neg, "roll").value, 2.0);
}

TEST(DecodeField, TrcQueryStateAndWrites) {
  const Decoded q = dec("#TPPD2rTRC0048", Dialect::topotek, Model::sip);
  ASSERT_NE(q.command, nullptr);
  EXPECT_TRUE(q.command->from_field());
  EXPECT_EQ(q.command->section.substr(0, 7), "field: ");
  EXPECT_EQ(q.role, Role::request);
  EXPECT_TRUE(codes(q).empty());
  const Decoded r = dec("#TPDP2rTRC0048", Dialect::topotek, Model::sip);
  EXPECT_EQ(r.role, Role::response);
  EXPECT_TRUE(codes(r).empty());
  EXPECT_EQ(field(r, "state").enum_name, "stopped");
  const struct {
    const char* data;
    const char* state;
  } states[] = {{"01", "waiting"},
                {"02", "tracking"},
                {"03", "temporarily_lost"},
                {"04", "lens_unsupported"}};
  for (const auto& s : states) {
    const Decoded x =
        dec(with_checksum(std::string("#TPDU2rTRC") + s.data), Dialect::topotek, Model::sip);
    EXPECT_EQ(field(x, "state").enum_name, s.state) << s.data;
    EXPECT_TRUE(codes(x).empty()) << s.data;
  }
  // ArduPilot's driver's writes: prepare, cancel to waiting, exit.
  EXPECT_EQ(field(dec("#TPUD2wTRC0254", Dialect::topotek), "action").enum_name, "prepare");
  EXPECT_EQ(field(dec("#TPUD2wTRC0153", Dialect::topotek), "action").enum_name,
            "cancel_to_waiting");
  EXPECT_EQ(field(dec("#TPUD2wTRC0052", Dialect::topotek), "action").enum_name, "exit");
  EXPECT_TRUE(codes(dec("#TPUD2rTRC004D", Dialect::topotek)).empty());
}

TEST(DecodeField, TraReplyOfAHealthyTracker) {
  EXPECT_TRUE(codes(dec("#TPPD2rTRA0046", Dialect::topotek, Model::sip)).empty());
  const Decoded r = dec("#TPDP2rTRA1148", Dialect::topotek, Model::sip);
  ASSERT_NE(r.command, nullptr);
  EXPECT_EQ(r.command->ident, "TRA");
  EXPECT_TRUE(codes(r).empty());
  EXPECT_EQ(field(r, "fault").text, "11");  // a code whose meaning no source gives
}

TEST(DecodeField, Pa2ModelName) {
  EXPECT_TRUE(codes(dec("#TPUG2rPA2002A", Dialect::topotek, Model::sip)).empty());
  const Decoded r = dec("#TPUG6rPA2SIM_TPBA", Dialect::topotek);  // ArduPilot's SIM_Topotek
  ASSERT_NE(r.form, nullptr);
  EXPECT_EQ(field(r, "model").text, "SIM_TP");
}

// PixEagle's centre-point LOC to a real SIP, byte for byte.
TEST(DecodeField, LocPointIsBigEndian) {
  const std::string bytes = from_hex("237470504441774c4f4300000000003e006f00094537");
  ASSERT_EQ(bytes.substr(0, 10), "#tpPDAwLOC");
  const Decoded d = dec(bytes, Dialect::topotek, Model::sip);
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "LOC");
  EXPECT_TRUE(codes(d).empty()) << d.summary();
  EXPECT_EQ(field(d, "x").integer, 0);
  EXPECT_EQ(field(d, "y").integer, 0);
  EXPECT_EQ(field(d, "width").integer, 62);
  EXPECT_EQ(field(d, "height").integer, 111);
  EXPECT_EQ(field(d, "mode").integer, 9);
  EXPECT_EQ(field(d, "mode").enum_name, "point");
  EXPECT_EQ(field(d, "x").spec->kind, FieldKind::be_i16);
  // A rectangle left of and above the centre: x -405 (FE6B), y -389 (FE7B).
  const std::string rect =
      with_checksum(std::string("#tpUDAwLOC") + from_hex("FE6BFE7B00C800C80001"));
  const Decoded r = dec(rect, Dialect::topotek);
  EXPECT_TRUE(codes(r).empty()) << r.summary();
  EXPECT_EQ(field(r, "x").integer, -405);
  EXPECT_EQ(field(r, "y").integer, -389);
  EXPECT_EQ(field(r, "width").integer, 200);
  EXPECT_EQ(field(r, "mode").enum_name, "rectangle");
  // Outside the +/-1000 grid: x 1001 (03E9).
  const Decoded out =
      dec(with_checksum(std::string("#tpUDAwLOC") + from_hex("03E90000000000000001")),
          Dialect::topotek);
  EXPECT_EQ(codes(out), std::vector<FindingCode>{FindingCode::value_out_of_range});
}

// OFT: PixEagle's examples, little-endian pixels then the status char.
TEST(DecodeField, OftTrackingBoxIsLittleEndian) {
  auto oft = [](unsigned x, unsigned y, unsigned w, unsigned h, char status) {
    std::string d = "#tpDP9wOFT";
    for (unsigned v : {x, y, w, h}) {
      d += static_cast<char>(v & 0xFF);
      d += static_cast<char>(v >> 8);
    }
    d += status;
    return with_checksum(d);
  };
  const Decoded a = dec(oft(952, 536, 51, 30, '2'), Dialect::topotek, Model::sip);
  ASSERT_TRUE(clean_reply(a, "OFT"));
  EXPECT_EQ(field(a, "x").integer, 952);
  EXPECT_EQ(field(a, "y").integer, 536);
  EXPECT_EQ(field(a, "width").integer, 51);
  EXPECT_EQ(field(a, "height").integer, 30);
  EXPECT_EQ(field(a, "status").enum_name, "tracking");
  const Decoded b = dec(oft(1288, 590, 127, 81, '2'), Dialect::topotek, Model::sip);
  EXPECT_EQ(field(b, "x").integer, 1288);
  EXPECT_EQ(field(b, "height").integer, 81);
  const Decoded c = dec(oft(0, 0, 0, 0, '1'), Dialect::topotek, Model::sip);
  EXPECT_EQ(field(c, "status").enum_name, "stopped");
  EXPECT_EQ(field(c, "width").integer, 0);
}

// The LRF result is the document's X1X2X3X4X5.X6 in metres (Topotek 5.9),
// which ArduPilot's AP_Mount_Topotek.cpp @ d4209711 reads ("12345.6", or
// ERR). The catalog had a field form of 5 chars from "a real unit",
// #tpMU5wLRF500002E, which was topsim's own midpoint filler: no LRF form is
// the field's, and 5 digits are the document's result, in metres.
TEST(DecodeField, LrfResultIsTheDocumentsSevenChars) {
  const CommandSpec* lrf = find_command(Dialect::topotek, "LRF");
  ASSERT_NE(lrf, nullptr);
  for (const FormSpec& f : lrf->forms) EXPECT_FALSE(f.from_field()) << f.note;
  const Decoded d = dec(with_checksum("#tpMU7wLRF01234.5"), Dialect::topotek, Model::sip);
  ASSERT_NE(d.form, nullptr);
  EXPECT_TRUE(codes(d).empty()) << d.summary();
  EXPECT_DOUBLE_EQ(field(d, "distance").value, 1234.5);
  EXPECT_EQ(field(d, "distance").unit(), "m");
  const Decoded err = dec(with_checksum("#tpMU3wLRFERR"), Dialect::topotek, Model::sip);
  ASSERT_NE(err.form, nullptr);
  EXPECT_TRUE(codes(err).empty()) << err.summary();
  EXPECT_TRUE(field(err, "distance").none);
  const Decoded five = dec("#tpMU5wLRF500002E", Dialect::topotek, Model::sip);
  ASSERT_NE(five.form, nullptr);
  EXPECT_FALSE(five.form->from_field());
  EXPECT_EQ(field(five, "distance").unit(), "m");
}

TEST(DecodeField, BigEndianKindsEncodeAndName) {
  EXPECT_EQ(to_string(FieldKind::be_i16), "be_i16");
  EXPECT_EQ(field_kind_from_string("be_u16"), FieldKind::be_u16);
  const CommandSpec* loc = find_command(Dialect::topotek, "LOC");
  ASSERT_NE(loc, nullptr);
  const FormSpec& form = loc->forms[0];
  const EncodeValue v[] = {{-405}, {-389}, {200}, {200}, {1}};
  std::string data;
  ASSERT_TRUE(encode_fields(form, v, data));
  EXPECT_EQ(data, from_hex("FE6BFE7B00C800C80001"));
  const EncodeValue too_big[] = {{0}, {0}, {70000}, {0}, {1}};
  EXPECT_FALSE(encode_fields(form, too_big, data));
  EXPECT_EQ(example_data(form).size(), 10u);
}

// ---- A real Topotek camera's frames that neither document lists (issue 47
// part 4), byte for byte from PixEagle's bench: alireza787b/PixEagle @
// 3bea324, docs/reporting/agent-ops/codex-modernization/evidence/
// 2026-09-17-gimbal-control-bench/<session>/events.jsonl (each frame's first
// delivery, UTC).

namespace {

// The field `name` of record `n` (from 1), or null.
const FieldValue* record_field(const Decoded& d, std::string_view name, std::uint16_t n) {
  for (const FieldValue& f : d.fields)
    if (f.name() == name && f.record == n) return &f;
  return nullptr;
}

// The findings of a severity.
std::size_t count_severity(const Decoded& d, Severity s) {
  std::size_t n = 0;
  for (const Finding& f : d.findings) n += f.severity == s;
  return n;
}

}  // namespace

// ODR: #tP, a raw length byte 0x0D, a count and one record of six
// little-endian 16-bit fields (x, y, width, height, label, confidence x
// 10000). Session 20260917T071854Z-ai-observe, 2026-09-17T07:18:56.928933Z,
// 0.43 s after #TPPD2wFED1034.
TEST(DecodeField, OdrDetectionOfARealCamera) {
  const std::string raw = from_hex("23745044500d774f44520115060500650102047f0000004630");
  const ParseResult p = parse_exact(raw);
  ASSERT_EQ(p.status, ParseStatus::frame);
  EXPECT_EQ(p.frame.header, Header::ext8);
  EXPECT_EQ(p.frame.data_length, 13u);
  const Decoded d = decode(p.frame, {.dialect = Dialect::topotek, .model = Model::sip});
  ASSERT_TRUE(clean_reply(d, "ODR"));
  EXPECT_EQ(field(d, "count").integer, 1);
  EXPECT_EQ(field(d, "count").record, 0);
  ASSERT_EQ(d.fields.size(), 7u);
  const struct {
    const char* name;
    double value;
    const char* unit;
  } want[] = {{"x", 1557, "px"},      {"y", 5, "px"},     {"width", 357, "px"},
              {"height", 1026, "px"}, {"label", 127, ""}, {"confidence", 0, ""}};
  for (const auto& w : want) {
    const FieldValue* f = record_field(d, w.name, 1);
    ASSERT_NE(f, nullptr) << w.name;
    EXPECT_TRUE(f->valid) << w.name;
    EXPECT_DOUBLE_EQ(f->value, w.value) << w.name;
    EXPECT_EQ(f->unit(), w.unit) << w.name;
    EXPECT_EQ(field_key(*f), std::string(w.name) + "[1]");
  }
  EXPECT_EQ(d.summary(),
            "count 1, x[1] 1557 px, y[1] 5 px, width[1] 357 px, height[1] 1026 px, "
            "label[1] 127, confidence[1] 0.0000");
  // Session 20260917T072135Z-ai-select, 07:21:37.929076Z: almost the whole frame.
  const Decoded wide = dec(from_hex("23745044500d774f445201090005006e0727047f0000003132"),
                           Dialect::topotek, Model::sip);
  EXPECT_TRUE(codes(wide).empty()) << wide.summary();
  EXPECT_EQ(record_field(wide, "x", 1)->integer, 9);
  EXPECT_EQ(record_field(wide, "width", 1)->integer, 1902);
  EXPECT_EQ(record_field(wide, "height", 1)->integer, 1063);
  // A confidence of 0.5 is sent as 5000 (the PDF's scale).
  std::string half = raw.substr(0, 21) + std::string("\x88\x13", 2);
  const Decoded c = dec(with_checksum(half), Dialect::topotek);
  EXPECT_DOUBLE_EQ(record_field(c, "confidence", 1)->value, 0.5);
}

// ODR with no detection, and counts the data does not hold: every whole
// record the count covers is decoded, and a count that does not match the
// data is a data-length at the count, with and without detail.
TEST(DecodeField, OdrCountsThatDoNotFit) {
  const std::string record = from_hex("15060500650102047f000000");  // the real one
  auto odr = [&](unsigned char count, int records) {
    std::string f = "#tPDP";
    f += static_cast<char>(1 + 12 * records);
    f += "wODR";
    f += static_cast<char>(count);
    for (int i = 0; i < records; ++i) f += record;
    return with_checksum(f);
  };
  const Decoded none = dec(odr(0, 0), Dialect::topotek, Model::sip);
  EXPECT_TRUE(codes(none).empty()) << none.summary();
  ASSERT_EQ(none.fields.size(), 1u);
  EXPECT_EQ(none.summary(), "count 0");

  const Decoded two = dec(odr(2, 2), Dialect::topotek, Model::sip);
  EXPECT_TRUE(codes(two).empty()) << two.summary();
  ASSERT_EQ(two.fields.size(), 13u);
  EXPECT_EQ(record_field(two, "x", 2)->integer, 1557);

  struct Case {
    unsigned char count;
    int records;
    std::size_t decoded;  // records decoded
  } cases[] = {{2, 1, 1}, {255, 1, 1}, {1, 2, 1}, {0, 1, 0}, {3, 0, 0}};
  for (const Case& k : cases) {
    SCOPED_TRACE("count " + std::to_string(k.count) + ", records " + std::to_string(k.records));
    const std::string bytes = odr(k.count, k.records);
    const Decoded d = dec(bytes, Dialect::topotek, Model::sip);
    ASSERT_EQ(codes(d), std::vector<FindingCode>{FindingCode::data_length}) << d.summary();
    EXPECT_EQ(d.findings[0].severity, Severity::warning);
    EXPECT_EQ(d.findings[0].offset, 10u);  // the count
    EXPECT_EQ(d.fields.size(), 1 + 6 * k.decoded);
    // the verdict without detail (topdump stats) is the same
    const ParseResult p = parse_exact(bytes);
    detail::DecodeCache cache;
    for (int pass = 0; pass < 2; ++pass) {
      const Decoded lean =
          toptest::decode_cached(p.frame, {.dialect = Dialect::topotek, .detail = false}, cache);
      EXPECT_EQ(codes(lean), codes(d));
      EXPECT_TRUE(lean.fields.empty());
    }
  }
}

// ODZ: pushed while the lens zooms, ten bytes all zero, meaning unknown
// (PixEagle's phase 5 checkpoint: "Their meaning is unknown"): raw bytes,
// shown as hex, no warning. Session 20260917T050955Z-zoom,
// 2026-09-17T05:09:57.284912Z, 14 ms after #TPPM2wZMC0259.
TEST(DecodeField, OdzIsTenBytesOfUnknownMeaning) {
  const Decoded d =
      dec(from_hex("237470445041774f445a000000000000000000003430"), Dialect::topotek, Model::sip);
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "ODZ");
  EXPECT_EQ(d.role, Role::response);
  EXPECT_TRUE(codes(d).empty()) << d.summary();
  ASSERT_EQ(d.fields.size(), 1u);
  EXPECT_EQ(d.fields[0].spec->kind, FieldKind::raw);
  EXPECT_EQ(d.fields[0].text, std::string(10, '\0'));
  EXPECT_EQ(d.summary(), "data 00 00 00 00 00 00 00 00 00 00");  // no control byte in any output
  EXPECT_NE(d.command->note.find("meaning"), std::string_view::npos);
  // Raw bytes that are printable stay as they are (Topotek AWB, appendix II).
  EXPECT_EQ(dec("#TPUD2wAWB0144", Dialect::topotek).summary(), "data 01");
}

// FED: PixEagle's detection output switch, 10 on and 20 off (sessions
// 20260917T071854Z-ai-observe 07:18:56.503172Z and 07:19:03.716098Z), never
// answered; it switches the ODR stream, an event push that no stream judge
// judges, as are OFT (while tracking) and ODZ (while zooming).
TEST(DecodeField, FedSwitchesTheDetectionsAndEventPushesAreNotPeriodic) {
  const Decoded on = dec("#TPPD2wFED1034", Dialect::topotek, Model::sip);
  ASSERT_NE(on.command, nullptr);
  EXPECT_TRUE(codes(on).empty()) << on.summary();
  EXPECT_EQ(field(on, "output").enum_name, "on");
  EXPECT_EQ(field(dec("#TPPD2wFED2035", Dialect::topotek), "output").enum_name, "off");
  EXPECT_EQ(write_reply(*on.command), WriteReply::nothing);
  ASSERT_NE(on.switches, nullptr);
  EXPECT_EQ(on.switches->push, "ODR");
  EXPECT_EQ(on.switches->sender, Sender::device);
  EXPECT_FALSE(on.switches->periodic);
  EXPECT_FALSE(on.switches->evidence.empty());
  EXPECT_TRUE(switches_off(*on.switches, 0x20));
  EXPECT_FALSE(switches_off(*on.switches, 0x10));
  EXPECT_FALSE(switches_off(*on.switches, 0x00));
  EXPECT_EQ(stream_enabled_by(Dialect::topotek, "FED", Profile::document), nullptr);
  for (const char* push : {"OFT", "ODR", "ODZ"}) {
    const StreamSpec* s = stream_of(Dialect::topotek, push);
    ASSERT_NE(s, nullptr) << push;
    EXPECT_FALSE(s->periodic) << push;
    EXPECT_TRUE(s->from_field()) << push;
  }
  // The documents' streams run at a rate (GAA's asked, the device's own).
  for (const StreamSpec& s : streams())
    if (!s.from_field()) {
      EXPECT_TRUE(s.periodic) << s.request << " -> " << s.push;
      EXPECT_EQ(s.off, 0u) << s.request;
    }
  const Decoded zoom = dec("#TPPM2wZMC0259", Dialect::topotek, Model::sip);
  ASSERT_NE(zoom.switches, nullptr);
  EXPECT_EQ(zoom.switches->push, "ODZ");
}

// OFT status '3': the target is lost for a moment, the box frozen (with
// TRC state 03 in 20260918T060352Z-point); a real camera sent it in
// 20260917T051606Z-point at 2026-09-17T05:16:08.998653Z between '2' boxes.
// It decodes without a warning (it was value-out-of-range).
TEST(DecodeField, OftStatus3IsTemporarilyLost) {
  const std::string raw = from_hex("237470445039774f4654a703230223001600333646");
  const Decoded d = dec(raw, Dialect::topotek, Model::sip);
  EXPECT_TRUE(codes(d).empty()) << d.summary();
  EXPECT_EQ(field(d, "status").enum_name, "temporarily_lost");
  EXPECT_EQ(field(d, "x").integer, 935);
  EXPECT_EQ(field(d, "height").integer, 22);
  const ParseResult p = parse_exact(raw);
  const Decoded lean = decode(p.frame, {.dialect = Dialect::topotek, .detail = false});
  EXPECT_TRUE(lean.findings.empty());
}

// FAI of 14 chars, as ArduPilot's SkyDroid driver sends it
// (AP_Mount_SkyDroid.cpp @ c5aa8452 send_attitude_to_gimbal(),
// "%04X%04X%04X%02X": yaw, pitch, roll and a mode byte, 1 fixed-wing, 0
// hover): the field's form, no warning but a data-length of information
// that names the driver; a device of the field profile takes it, the
// document's (SkyDroid 3.3.6.2: 12 chars) refuses it.
TEST(DecodeField, Fai14CharsIsTheDriversForm) {
  for (Model m : {Model::c12, Model::c13}) {
    SCOPED_TRACE(std::string(to_string(m)));
    const Decoded d = dec(with_checksum("#tpUGEwFAIEC78FF38000001"), Dialect::skydroid, m);
    ASSERT_NE(d.form, nullptr);
    EXPECT_TRUE(d.form->from_field());
    EXPECT_EQ(count_severity(d, Severity::warning) + count_severity(d, Severity::error), 0u)
        << d.summary();
    // (on a C13 also the unsupported-on-model of information: the driver
    // sends the C13 the C11's commands)
    const Finding* length = nullptr;
    for (const Finding& x : d.findings) {
      if (x.code == FindingCode::data_length) length = &x;
      EXPECT_EQ(x.severity, Severity::info) << x.message;
    }
    ASSERT_NE(length, nullptr) << d.summary();
    EXPECT_EQ(length->offset, 10u);
    EXPECT_NE(length->message.find("FAI 'w' takes 12 in SkyDroid 3.3.6.2"), std::string::npos)
        << length->message;
    EXPECT_NE(length->quirk.find("AP_Mount_SkyDroid.cpp @ c5aa8452"), std::string::npos);
    EXPECT_DOUBLE_EQ(field(d, "yaw").value, -50.0);
    EXPECT_DOUBLE_EQ(field(d, "pitch").value, -2.0);
    EXPECT_EQ(field(d, "mode").enum_name, "fixed_wing");
    EXPECT_EQ(rejection(d, m, true), Rejection::none);
    EXPECT_NE(rejection(d, m, false), Rejection::none);  // the document's device refuses it
  }
  const Decoded hover = dec(with_checksum("#tpUGEwFAI00000000000000"), Dialect::skydroid);
  EXPECT_EQ(field(hover, "mode").enum_name, "hover");
  // The document's 12 chars are the document's form, no finding.
  const Decoded doc = dec("#TPUGCwFAIEC780000000064", Dialect::skydroid, Model::c12);
  ASSERT_NE(doc.form, nullptr);
  EXPECT_FALSE(doc.form->from_field());
  EXPECT_EQ(count_severity(doc, Severity::warning), 0u) << doc.summary();
  // A device's echo of it is the device's frame: no note.
  const Decoded echo = dec(with_checksum("#tpGUEwFAIEC78FF38000001"), Dialect::skydroid);
  EXPECT_TRUE(codes(echo).empty()) << echo.summary();
}
