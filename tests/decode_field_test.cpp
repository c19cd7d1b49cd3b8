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
  ASSERT_NE(a.command, nullptr);
  EXPECT_EQ(a.command->ident, "OFT");
  EXPECT_EQ(a.role, Role::response);
  EXPECT_TRUE(codes(a).empty()) << a.summary();
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
