// Every finding code: documented in docs/FINDINGS.md, and proven to fire.
#include "top/findings.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "test_util.hpp"

using namespace top;

namespace {

struct Trigger {
  std::string bytes;
  Dialect dialect = Dialect::unknown;
  Model model = Model::unknown;
};

// One input per code that must produce it (through the stream decoder and
// the catalog, as topdump sees it).
const std::map<FindingCode, Trigger>& triggers() {
  static const std::map<FindingCode, Trigger> t = {
      {FindingCode::bad_checksum, {"#TPUD2wCAP0100"}},
      {FindingCode::checksum_header_case, {"#TPUG6wGAYEF073288", Dialect::skydroid}},
      {FindingCode::checksum_case, {"#tpUM2rZOM00a3"}},
      {FindingCode::no_checksum, {"#TPUD2wCAP01"}},
      {FindingCode::length_mismatch, {"#tpDU3rVER0105025A"}},
      {FindingCode::tp_length, {with_checksum("#TPUD4wEXT0000"), Dialect::skydroid}},
      {FindingCode::bad_header, {"#X#TPUD2wCAP013E"}},
      {FindingCode::bad_address, {"#TPXD2wCAP013E"}},
      {FindingCode::bad_control, {"#TPUD2xCAP013E"}},
      {FindingCode::bad_length_char, {"#TPUDZwCAP013E"}},
      {FindingCode::bad_ident, {"#TPUD2wCaP013E"}},
      {FindingCode::truncated, {"#TPUD2wCAP0"}},
      {FindingCode::trailing_bytes, {"#TPUD2wCAP013Exyz"}},
      {FindingCode::garbage, {"xyz#TPUD2wCAP013E"}},
      {FindingCode::crlf, {"#TPUD2wCAP013E\r\n"}},
      {FindingCode::lowercase_hex, {with_checksum("#tpUG6wGAYec7832"), Dialect::topotek}},
      {FindingCode::frame_too_long, {"#TpUD\xff\xffGPS"}},
      {FindingCode::tmp_quirk, {with_checksum("#PDP16TMP" + std::string(22, '0'))}},
      {FindingCode::two_digit_length, {with_checksum("#tpUD10wIPV" + std::string(16, '1'))}},
      {FindingCode::ext_header_skydroid,
       {build_frame({.header = Header::ext8,
                     .src = 'U',
                     .dst = 'D',
                     .control = 'w',
                     .ident = "CAP",
                     .data = "01"}),
        Dialect::skydroid}},
      {FindingCode::unknown_ident, {"#TPUD2wQQQ0155"}},
      {FindingCode::unsupported_on_model, {"#TPUG2wPTZ006A", Dialect::skydroid, Model::c13}},
      {FindingCode::unsupported_control, {with_checksum("#TPUG2rPTZ00"), Dialect::skydroid}},
      {FindingCode::data_length, {with_checksum("#tpUG4wGAYEC78"), Dialect::skydroid}},
      {FindingCode::bad_field, {with_checksum("#tpUG6wGAYZZ7832"), Dialect::skydroid}},
      {FindingCode::value_out_of_range, {with_checksum("#tpUG6wGAY2EE032"), Dialect::skydroid}},
      {FindingCode::error_reply, {"#TPMU2wERE!!30", Dialect::skydroid}},
      {FindingCode::unswapped_addresses, {"#tpUDDrIPV192.168.31.22D2", Dialect::skydroid}},
      {FindingCode::length_in_bytes, {with_checksum("#TPDU1rIMG01")}},
      {FindingCode::double_checksum, {"#TPUG2wPTZ056FEB"}},
  };
  return t;
}

std::vector<Finding> findings_of(const Trigger& t) {
  std::vector<Finding> out;
  if (t.bytes.find("xyz") != std::string::npos && t.bytes.back() == 'z') {
    // trailing-bytes is the verdict of a one-frame buffer.
    ParseResult r = parse_exact(t.bytes);
    return r.frame.findings;
  }
  top::StreamDecoder d(top::StreamOptions{ParseOptions{.max_data_length = 4096}});
  d.feed(t.bytes);
  d.finish();
  StreamItem it;
  while (d.next(it)) {
    if (it.kind == ItemKind::garbage) {
      out.push_back(it.finding);
      continue;
    }
    for (auto& f : it.frame.findings) out.push_back(f);
    DecodeOptions o;
    o.dialect = t.dialect;
    o.model = t.model;
    Decoded dec = decode(it.frame, o);
    for (auto& f : dec.findings) out.push_back(f);
  }
  return out;
}

}  // namespace

TEST(Findings, TableIsComplete) {
  std::set<std::string_view> seen;
  for (std::size_t i = 0; i < finding_code_count; ++i) {
    auto c = static_cast<FindingCode>(i);
    std::string_view s = to_string(c);
    EXPECT_TRUE(seen.insert(s).second) << "duplicate code " << s;
    EXPECT_EQ(finding_code_from_string(s), c);
    EXPECT_FALSE(description(c).empty());
    for (char ch : s) EXPECT_TRUE((ch >= 'a' && ch <= 'z') || ch == '-') << s;
  }
  EXPECT_FALSE(finding_code_from_string("no-such-code").has_value());
}

TEST(Findings, EveryCodeIsDocumented) {
  std::ifstream in(std::string(TOPKIT_SOURCE_DIR) + "/docs/FINDINGS.md");
  ASSERT_TRUE(in) << "docs/FINDINGS.md missing";
  std::stringstream ss;
  ss << in.rdbuf();
  std::string doc = ss.str();
  for (std::size_t i = 0; i < finding_code_count; ++i) {
    auto c = static_cast<FindingCode>(i);
    std::string row = "| `" + std::string(to_string(c)) + "` | " +
                      std::string(to_string(default_severity(c))) + " |";
    EXPECT_NE(doc.find(row), std::string::npos) << "docs/FINDINGS.md lacks the row " << row;
  }
}

// The "Quirks" table of docs/FINDINGS.md has one row per quirk id of the
// table, "| `quirk id` | `code` | behaviour |", and no other.
TEST(Findings, EveryQuirkIsDocumented) {
  std::ifstream in(std::string(TOPKIT_SOURCE_DIR) + "/docs/FINDINGS.md");
  ASSERT_TRUE(in) << "docs/FINDINGS.md missing";
  std::set<std::string> documented, expected;
  bool in_quirks = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0) in_quirks = line == "## Quirks";
    if (!in_quirks || line.rfind("| `", 0) != 0) continue;
    const auto second = line.find(" | ", 1);
    ASSERT_NE(second, std::string::npos) << line;
    const auto third = line.find(" | ", second + 3);
    ASSERT_NE(third, std::string::npos) << line;
    documented.insert(line.substr(0, third + 3));
  }
  for (std::size_t i = 0; i < finding_code_count; ++i) {
    auto c = static_cast<FindingCode>(i);
    if (quirk_id(c).empty()) continue;
    expected.insert("| `" + std::string(quirk_id(c)) + "` | `" + std::string(to_string(c)) +
                    "` | ");
  }
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(documented, expected);
}

TEST(Findings, EveryCodeHasATrigger) { EXPECT_EQ(triggers().size(), finding_code_count); }

class FindingFires : public ::testing::TestWithParam<std::size_t> {};

TEST_P(FindingFires, Fires) {
  auto code = static_cast<FindingCode>(GetParam());
  auto it = triggers().find(code);
  ASSERT_NE(it, triggers().end()) << "no trigger for " << to_string(code);
  auto found = findings_of(it->second);
  bool hit = false;
  for (const auto& f : found) {
    if (f.code != code) continue;
    hit = true;
    EXPECT_FALSE(f.message.empty());
    // A code with a quirk id names it; another code's finding names a quirk
    // only as field evidence (decode's and the device rules').
    if (!quirk_id(code).empty()) {
      EXPECT_EQ(f.quirk, quirk_id(code));
    }
  }
  std::string got;
  for (const auto& f : found) got += std::string(to_string(f.code)) + " ";
  EXPECT_TRUE(hit) << to_string(code) << " did not fire; got: " << got;
}

INSTANTIATE_TEST_SUITE_P(AllCodes, FindingFires,
                         ::testing::Range<std::size_t>(0, finding_code_count),
                         [](const ::testing::TestParamInfo<std::size_t>& i) {
                           std::string s(to_string(static_cast<FindingCode>(i.param)));
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });
