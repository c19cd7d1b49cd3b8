#include "top/decode.hpp"

#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace top;

namespace {

Decoded dec(std::string_view bytes, Dialect d = Dialect::unknown, Model m = Model::unknown) {
  ParseResult r = parse_exact(bytes);
  EXPECT_EQ(r.status, ParseStatus::frame) << bytes;
  return decode(r.frame, {.dialect = d, .model = m});
}

const FieldValue& field(const Decoded& d, std::string_view name) {
  for (const auto& f : d.fields)
    if (f.name() == name) return f;
  static FieldValue none;
  ADD_FAILURE() << "no field " << name << " in " << d.summary();
  return none;
}

}  // namespace

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
  EXPECT_EQ(format_value(field(dec("#TPUG2wPTZ0670", Dialect::skydroid), "action")),
            "follow (06)");
}

TEST(Decode, UndocumentedEnumValue) {
  std::string s = build_frame({.header = Header::fixed, .src = 'U', .dst = 'G', .control = 'w',
                               .ident = "PTZ", .data = "7F"});
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
