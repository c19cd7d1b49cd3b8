#include "top/decode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "test_util.hpp"
#include "top/detail/decimal.hpp"

using namespace top;
using toptest::dec;
using toptest::field;
using toptest::tmp_quirk_frame;

TEST(Decode, AngleCommand) {
  Decoded d = dec("#tpUG6wGAYEC7832", Dialect::skydroid);
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "GAY");
  EXPECT_EQ(d.role, Role::request);
  const FieldValue& a = field(d, "angle");
  EXPECT_DOUBLE_EQ(a.value, -50.0);
  EXPECT_EQ(a.integer, -5000);
  EXPECT_EQ(a.unit(), "deg");
  EXPECT_EQ(a.offset, 10u);
  EXPECT_EQ(a.length, 4u);
  EXPECT_EQ(format_value(a), "-50.00 deg");
  EXPECT_DOUBLE_EQ(field(d, "speed").value, 5.0);
  EXPECT_EQ(d.summary(), "angle -50.00 deg, speed 5.0 deg/s");
  std::string s = "GAY: ";  // appended after what the buffer holds, separators as summary()'s
  d.append_summary(s);
  EXPECT_EQ(s, "GAY: angle -50.00 deg, speed 5.0 deg/s");
}

TEST(Decode, TpLengthSeverityDependsOnClassAndDialect) {
  Decoded g = dec("#TPUG6wGAYEF073248", Dialect::skydroid);
  ASSERT_EQ(g.findings.size(), 1u);
  EXPECT_EQ(g.findings[0].code, FindingCode::tp_length);
  EXPECT_EQ(g.findings[0].severity, Severity::info);
  Decoded t = dec("#TPUG6wGAYEF073248", Dialect::topotek);
  ASSERT_FALSE(t.findings.empty());
  EXPECT_EQ(t.findings[0].code, FindingCode::tp_length);
  EXPECT_EQ(t.findings[0].severity, Severity::warning);
}

TEST(Decode, EnumNamesPerDialect) {
  EXPECT_EQ(field(dec("#TPUG2wPTZ0670", Dialect::skydroid), "action").enum_name, "follow");
  EXPECT_EQ(field(dec("#TPUG2wPTZ0670", Dialect::topotek), "action").enum_name, "lock");
  EXPECT_EQ(format_value(field(dec("#TPUG2wPTZ0670", Dialect::skydroid), "action")), "follow (06)");
}

TEST(Decode, UndocumentedEnumValue) {
  std::string s = with_checksum("#TPUG2wPTZ7F");
  Decoded d = dec(s, Dialect::skydroid);
  EXPECT_TRUE(toptest::has_code(d.findings, FindingCode::value_out_of_range));
}

TEST(Decode, EncodeRoundTrip) {
  const CommandSpec* c = find_command(Dialect::skydroid, "GAY");
  ASSERT_NE(c, nullptr);
  EncodeValue v[2] = {{.number = -50.0}, {.number = 5.0}};
  std::string data;
  ASSERT_TRUE(encode_fields(c->forms[0], v, data));
  EXPECT_EQ(data, "EC7832");
  EncodeValue too_big[2] = {{.number = 400.0}, {.number = 5.0}};
  EXPECT_FALSE(encode_fields(c->forms[0], too_big, data));
}

TEST(Decode, AttitudeStream) {
  // A real Topotek reply (DESIGN.md field notes): addresses swapped.
  Decoded d = dec("#tpGPCrGACFF36ED5A0048DE");
  EXPECT_EQ(d.dialect, Dialect::topotek);
  EXPECT_EQ(d.role, Role::response);
  EXPECT_NEAR(field(d, "yaw").value, -2.02, 1e-9);
  EXPECT_NEAR(field(d, "pitch").value, -47.74, 1e-9);
  EXPECT_NEAR(field(d, "roll").value, 0.72, 1e-9);
  EXPECT_TRUE(d.findings.empty());
}

TEST(Decode, ZoomPositionIsSigned) {
  Decoded d = dec("#tpMU4rZOMFFB447");
  EXPECT_EQ(field(d, "position").integer, -76);
}

TEST(Decode, GpsBinaryStructLittleEndian) {
  std::string data;
  auto le = [&](std::uint32_t v, int n) {
    for (int i = 0; i < n; ++i) data += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  le(static_cast<std::uint16_t>(-1500), 2);
  le(static_cast<std::uint32_t>(1203456789), 4);
  le(static_cast<std::uint32_t>(-301234567), 4);
  le(static_cast<std::uint32_t>(123456), 4);
  std::string s = build_frame({.header = Header::variable,
                               .src = 'P',
                               .dst = 'D',
                               .control = 'w',
                               .ident = "GPS",
                               .data = data});
  Decoded d = dec(s);
  ASSERT_NE(d.command, nullptr);
  EXPECT_NEAR(field(d, "longitude").value, 120.3456789, 1e-9);
  EXPECT_NEAR(field(d, "latitude").value, -30.1234567, 1e-9);
  EXPECT_NEAR(field(d, "altitude").value, 123.456, 1e-9);
  EXPECT_EQ(field(d, "longitude").unit(), "deg");
  for (const auto& f : d.findings) EXPECT_NE(f.severity, Severity::error) << f.message;
}

TEST(Decode, TmpQuirkTemperatures) {
  Decoded d = dec(tmp_quirk_frame());
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "TMP");
  EXPECT_EQ(field(d, "x_high").integer, 0xA0);
  EXPECT_NEAR(field(d, "t_high").value, 50.0, 1e-9);
  EXPECT_NEAR(field(d, "t_low").value, -20.0, 1e-9);
  EXPECT_NEAR(field(d, "t_center").value, 29.1, 1e-9);
  EXPECT_EQ(field(d, "t_center").unit(), "degC");
}

TEST(Decode, IpAddressAndCardCapacity) {
  Decoded ip = dec("#tpUDDwIPV192.168.31.22D7", Dialect::skydroid);
  EXPECT_EQ(field(ip, "address").text, "192.168.31.22");
  std::string sdc = with_checksum("#tpDUArSDC0123400ABC");
  Decoded d = dec(sdc, Dialect::skydroid);
  EXPECT_EQ(field(d, "free").integer, 0x01234);
  EXPECT_EQ(field(d, "total").integer, 0x00ABC);
  EXPECT_EQ(format_value(field(d, "free")), "4660 MB");
  std::string none = with_checksum("#tpDP5rSDCNNNNN");
  Decoded n = dec(none, Dialect::topotek);
  ASSERT_FALSE(n.fields.empty());
  EXPECT_TRUE(n.fields[0].none);
}

TEST(Decode, LowercaseHexDataIsDecodedAndReported) {
  std::string s = with_checksum("#tpUG6wGAYec7832");
  Decoded d = dec(s, Dialect::topotek);
  EXPECT_DOUBLE_EQ(field(d, "angle").value, -50.0);
  EXPECT_TRUE(toptest::has_code(d.findings, FindingCode::lowercase_hex));
}

TEST(Decode, UnknownIdentKeepsTheFrame) {
  Decoded d = dec("#TPUD2wQQQ0155", Dialect::skydroid);
  EXPECT_EQ(d.command, nullptr);
  EXPECT_TRUE(toptest::has_code(d.findings, FindingCode::unknown_ident));
}

TEST(Decode, ExampleDataDecodesCleanForEveryForm) {
  for (Dialect dl : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& c : commands(dl))
      for (const FormSpec& f : c.forms) {
        std::string data = example_data(f);
        EXPECT_GE(data.size(), f.min_length) << c.ident;
        EXPECT_LE(data.size(), f.max_length) << c.ident;
      }
}

TEST(Decode, SkydroidNoCardIsNotZeroMegabytes) {
  std::string s = with_checksum("#tpDUArSDC0000000000");
  Decoded d = dec(s, Dialect::skydroid);
  ASSERT_EQ(d.fields.size(), 2u);
  EXPECT_TRUE(d.fields[0].none);
  EXPECT_TRUE(d.fields[1].none);
  EXPECT_EQ(d.summary(), "none (all zero: no memory card)");
  // A full card (no MB free) is not "no card".
  std::string full = with_checksum("#tpDUArSDC000001D1C0");
  Decoded f = dec(full, Dialect::skydroid);
  EXPECT_FALSE(f.fields[0].none);
  EXPECT_EQ(f.fields[0].integer, 0);
  EXPECT_EQ(f.fields[1].integer, 0x1D1C0);
}

// format_value writes numbers as printf("%.*f") would (it uses std::to_chars,
// which promises the same text): every numeric field of the catalog, with
// values across its range and beyond, and huge decimal numbers.
TEST(Decode, FormatValueNumbersAreThoseOfPrintf) {
  auto decimals = [](double scale) {  // as decode.cpp decides them
    int d = 0;
    double s = scale;
    while (d < 9 && scale > 0 && std::fabs(s - std::round(s)) > 1e-9) {
      s *= 10;
      ++d;
    }
    return d;
  };
  auto printf_text = [](double v, int d) {
    std::vector<char> b(static_cast<std::size_t>(std::snprintf(nullptr, 0, "%.*f", d, v)) + 1);
    std::snprintf(b.data(), b.size(), "%.*f", d, v);
    return std::string(b.data());
  };
  std::size_t checked = 0;
  std::uint64_t x = 88172645463325252ull;
  auto rnd = [&] {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  for (Dialect dl : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& c : commands(dl))
      for (const FormSpec& form : c.forms)
        for (const FieldSpec& s : form.fields) {
          if (s.kind != FieldKind::hex_u && s.kind != FieldKind::hex_s &&
              s.kind != FieldKind::dec_u && s.kind != FieldKind::le_i16 &&
              s.kind != FieldKind::le_u16 && s.kind != FieldKind::le_i32 &&
              s.kind != FieldKind::number)
            continue;
          for (int i = 0; i < 200; ++i) {
            FieldValue fv;
            fv.spec = &s;
            fv.valid = true;
            fv.integer = static_cast<std::int64_t>(rnd() % 2000001) - 1000000;
            if (i % 4 == 0) fv.integer = static_cast<std::int64_t>(rnd() >> (rnd() % 64));
            fv.value = static_cast<double>(fv.integer) * s.scale;
            const int d = decimals(s.scale);
            const double m = std::round(s.scale * std::pow(10.0, d));
            if (i % 2 && std::fabs(static_cast<double>(fv.integer) * m) < 1e15)
              fv.value = static_cast<double>(fv.integer) * m / std::pow(10.0, d);  // as decoded
            if (s.kind == FieldKind::number) {
              fv.text = "12.5";
              continue;  // printed as its text
            }
            std::string want = printf_text(fv.value, d);
            if (!s.unit.empty()) want += " " + std::string(s.unit);
            const std::string got = format_value(fv);
            ASSERT_EQ(got.substr(0, want.size()), want) << s.name << " " << fv.integer;
            ++checked;
          }
        }
  EXPECT_GT(checked, 5000u);
  // past the 64-character buffer: a 1e300 value in a decimal field
  static const FieldSpec big{"big", FieldKind::hex_u, 2, 0.5, "", 0, -1};
  FieldValue fv;
  fv.spec = &big;
  fv.valid = true;
  fv.value = 1e300;
  EXPECT_EQ(format_value(fv), printf_text(1e300, 1));
}

// A scaled value is the double nearest to its decimal: 70 x 0.01 is 0.7, not
// 0.7000000000000001 (what the multiplication gives, and what topdump --json
// printed for about one field in six of the benchmark capture).
TEST(Decode, ScaledValuesAreTheNearestDoubleToTheirDecimal) {
  ParseResult r = parse_exact(with_checksum("#TPGUCrGAC0046FFAD0053"));
  ASSERT_EQ(r.status, ParseStatus::frame);
  const Decoded d = decode(r.frame, {.dialect = Dialect::skydroid});
  EXPECT_EQ(field(d, "yaw").value, 0.7);
  EXPECT_EQ(field(d, "pitch").value, -0.83);
  EXPECT_EQ(field(d, "roll").value, 0.83);
  std::int64_t mant = 0;
  int dec = 0;
  ASSERT_TRUE(detail::exact_decimal(field(d, "pitch"), mant, dec));
  EXPECT_EQ(mant, -83);
  EXPECT_EQ(dec, 2);
  EXPECT_EQ(format_value(field(d, "pitch")), "-0.83 deg");
}

// An enum_hex code is written as printf("%0*llX", width, value) would: the
// field's width, wider when the value needs more digits; with its name or
// "(undocumented)". append_value appends to what the buffer holds.
TEST(Decode, EnumCodesAreThoseOfPrintf) {
  static constexpr EnumValue kNames[] = {{0x06, "follow"}};
  FieldSpec spec;
  spec.name = "action";
  spec.kind = FieldKind::enum_hex;
  spec.enums = kNames;
  std::size_t checked = 0;
  for (std::uint32_t width = 0; width <= 17; ++width)
    for (std::uint64_t v : {0x0ull, 0x6ull, 0x7Full, 0x1ABull, 0xFFFFull, 0x123456789ABCDEFull,
                            0xFEDCBA9876543210ull}) {
      FieldValue f;
      f.spec = &spec;
      f.valid = true;
      f.length = width;
      f.integer = static_cast<std::int64_t>(v);
      f.enum_name = v == 0x6 ? "follow" : "";
      char b[64];
      std::snprintf(b, sizeof b, "%0*llX", static_cast<int>(width),
                    static_cast<unsigned long long>(v));
      const std::string want =
          v == 0x6 ? "follow (" + std::string(b) + ")" : std::string(b) + " (undocumented)";
      EXPECT_EQ(format_value(f), want) << width << " " << v;
      std::string appended = "x=";
      append_value(f, appended);
      EXPECT_EQ(appended, "x=" + want);
      ++checked;
    }
  EXPECT_EQ(checked, 18u * 7u);
}

// topsim answers LAT/LON writes in 5.8.7's layout (W0000000090,
// S000000045): no digits-and-point coordinate of 5.8.1/5.8.2, so they decode
// as the output, not as the writes' layout (they did: every digit string
// passed as dddmm.mmmm), and the catalog's example data is a valid
// coordinate.
TEST(Decode, DocumentOutputIsNotTakenForTheWritesLayout) {
  for (const char* raw : {"#tpDUBwLONW0000000090", "#tpDUAwLATS000000045"}) {
    const Decoded out = dec(with_checksum(raw), Dialect::topotek, Model::sip);
    ASSERT_NE(out.form, nullptr) << raw;
    EXPECT_TRUE(out.findings.empty()) << raw << ": " << out.findings.front().message;
    EXPECT_FALSE(out.form->from_field()) << raw;
    EXPECT_EQ(field(out, "hemisphere").text, std::string(1, raw[10])) << raw;
  }
  // The writes themselves: a coordinate out of shape is a bad field.
  for (const char* raw : {"#tpUDAwLATN35201.206", "#tpUDAwLATE3520.1206", "#tpUDBwLONE13883.6200",
                          "#tpUDBwLONE1384362000"}) {
    const Decoded w = dec(with_checksum(raw), Dialect::topotek, Model::sip);
    EXPECT_TRUE(toptest::has_code(w.findings, FindingCode::bad_field)) << raw;
  }
  // An LRF result has one layout, the document's X1X2X3X4X5.X6 (there was
  // a field form of 5 digits, #tpMU5wLRF500002E, which was topsim's own
  // midpoint filler and no device's): whatever the order, the document's.
  for (const char* raw : {"#tpMU7wLRF01234.5", "#tpMU5wLRF50000"}) {
    const top::ParseResult lrf = top::parse_exact(with_checksum(raw));
    for (bool document_first : {false, true}) {
      const Decoded d = decode(lrf.frame, {.dialect = Dialect::topotek,
                                           .model = Model::sip,
                                           .role = Role::response,
                                           .document_first = document_first});
      ASSERT_NE(d.form, nullptr) << raw;
      EXPECT_TRUE(d.findings.empty()) << raw << ": " << d.findings.front().message;
      EXPECT_FALSE(d.form->from_field()) << raw;
      EXPECT_EQ(field(d, "distance").unit(), "m") << raw;
    }
  }
  for (const char* id : {"LAT", "LON"}) {
    const top::CommandSpec* c = top::find_command(Dialect::topotek, id);
    ASSERT_NE(c, nullptr);
    const std::string data = top::example_data(c->forms[0]);
    const Decoded w =
        dec(with_checksum(std::string("#tpUD") + (data.size() == 10 ? "A" : "B") + "w" + id + data),
            Dialect::topotek, Model::sip);
    EXPECT_TRUE(w.findings.empty()) << id << " " << data;
  }
}

// LAT/LON answers: 5.8.7's output (hemisphere + degrees) is the one
// answer a source gives (there was a field form of the write's echo, which
// no source records). A device frame in the write's own layout is not taken
// for a second answer: it reads as the output, its degrees out of range.
TEST(Decode, PositionAnswersAreTheDocumentsOutput) {
  const Decoded echo = dec(with_checksum("#tpDUAwLATN2232.7680"), Dialect::topotek, Model::sip);
  ASSERT_NE(echo.form, nullptr);
  EXPECT_FALSE(echo.form->from_field());
  EXPECT_TRUE(toptest::has_code(echo.findings, FindingCode::value_out_of_range)) << echo.summary();
  for (const char* id : {"LAT", "LON"}) {
    const top::CommandSpec* c = top::find_command(Dialect::topotek, id);
    ASSERT_NE(c, nullptr);
    for (const top::FormSpec& f : c->forms) EXPECT_FALSE(f.from_field()) << id;
  }
  const Decoded out = dec(with_checksum("#tpDUBwLONW 74.006000"), Dialect::topotek, Model::sip);
  ASSERT_NE(out.form, nullptr);
  EXPECT_TRUE(out.findings.empty()) << out.findings.front().message;
  EXPECT_EQ(field(out, "hemisphere").text, "W");
  EXPECT_NEAR(field(out, "longitude").value, 74.006, 1e-6);
  // Without detail (the shape cache's path) the same form and no finding.
  top::ParseResult r = top::parse_exact(with_checksum("#tpDUBwLONW 74.006000"));
  detail::DecodeCache cache;
  for (int i = 0; i < 2; ++i) {
    const Decoded fast = toptest::decode_cached(
        r.frame, {.dialect = Dialect::topotek, .model = Model::sip, .detail = false}, cache);
    EXPECT_EQ(fast.form, out.form);
    EXPECT_TRUE(fast.findings.empty());
  }
}

// A frame the device sent in the request's address order (DecodeOptions
// role response) gets its unswapped-addresses finding from the device's
// form, after the findings of its fields (as the Lua dissector lists
// them), with detail, without, and from the shape cache.
TEST(Decode, DeviceFormFindingComesAfterTheFieldsFindings) {
  const std::string s = with_checksum("#tpUG6wGAYec7832");  // lowercase hex data
  const ParseResult r = parse_frame(s, true);
  ASSERT_EQ(r.status, ParseStatus::frame);
  detail::DecodeCache cache;
  for (bool detail : {true, false})
    for (int pass = 0; pass < 2; ++pass) {
      DecodeOptions o{Dialect::skydroid, Model::unknown, Role::response};
      o.detail = detail;
      const Decoded d = detail ? decode(r.frame, o) : toptest::decode_cached(r.frame, o, cache);
      std::vector<FindingCode> codes;
      for (const Finding& x : d.findings) codes.push_back(x.code);
      EXPECT_EQ(codes, (std::vector<FindingCode>{FindingCode::lowercase_hex,
                                                 FindingCode::unswapped_addresses}))
          << "detail " << detail << " pass " << pass;
    }
}
