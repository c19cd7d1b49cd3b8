// The fuzzing support code is itself tested: a mutator that repaired
// nothing, a reference parser that accepted everything or a dictionary the
// engine cannot read would make every fuzz run pass for the wrong reason.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "check.hpp"
#include "json_check.hpp"
#include "mutator.hpp"
#include "reference.hpp"
#include "top/top.hpp"

using namespace top;

namespace {

std::string repaired(std::string s) {
  topfuzz::repair_frames(reinterpret_cast<std::uint8_t*>(s.data()), s.size());
  return s;
}

// One libFuzzer dictionary line: kw<N>="<printable, \\, \" or \xHH>".
bool dict_entry(const std::string& line) {
  std::size_t i = 0;
  if (line.compare(0, 2, "kw") != 0) return false;
  for (i = 2; i < line.size() && line[i] >= '0' && line[i] <= '9'; ++i) {
  }
  if (i == 2 || line.compare(i, 2, "=\"") != 0) return false;
  for (i += 2; i + 1 < line.size(); ++i) {
    const char c = line[i];
    if (c == '"' || c < 0x20 || c > 0x7E) return false;
    if (c != '\\') continue;
    const char e = line[++i];
    if (e == 'x') {
      if (i + 2 >= line.size() || !std::isxdigit(static_cast<unsigned char>(line[i + 1])) ||
          !std::isxdigit(static_cast<unsigned char>(line[i + 2])))
        return false;
      i += 2;
    } else if (e != '\\' && e != '"') {
      return false;
    }
  }
  return i == line.size() - 1 && line.back() == '"';
}

bool clean(std::string_view s) {
  ParseResult r = parse_exact(s);
  return r.status == ParseStatus::frame && r.frame.checksum_ok && r.frame.findings.empty();
}

}  // namespace

TEST(Mutator, RepairsLengthAndChecksumOfEachHeader) {
  // Wrong length char and checksum.
  EXPECT_EQ(repaired("#tpUG3wGAYEF0732XX"), "#tpUG6wGAYEF073288");
  EXPECT_TRUE(clean(repaired("#TPUG9wPTZ0600")));
  // #tP: raw length byte; #Tp: two raw length bytes.
  std::string ext8 = repaired(std::string("#tPUD\x01wGPS0123456789ZZ"));
  EXPECT_EQ(static_cast<unsigned char>(ext8[5]), 10u);
  EXPECT_TRUE(clean(ext8));
  std::string ext16 = repaired(std::string("#TpUD\x09\x09LOCabcdefZZ", 18));
  EXPECT_EQ(ext16[5], 0);
  EXPECT_EQ(ext16[6], 6);
  EXPECT_TRUE(clean(ext16));
}

TEST(Mutator, RepairsEveryFrameOfABufferAndKeepsItsSize) {
  const std::string in = "xx#tpUG0wGAYEF0732..\r\n#TPUG2wPTZ06!!#tpUM2wZMC00";
  const std::string out = repaired(in);
  ASSERT_EQ(out.size(), in.size());
  StreamDecoder d;
  d.feed(out);
  d.finish();
  StreamItem it;
  int frames = 0;
  while (d.next(it))
    if (it.kind == ItemKind::frame) {
      EXPECT_TRUE(it.frame.checksum_ok) << it.frame.raw;
      ++frames;
    }
  EXPECT_EQ(frames, 3);
}

TEST(Mutator, CapsTheLengthAtTheHeaderMaximum) {
  // 20 data chars do not fit a hex digit: length F, checksum after 15.
  const std::string out = repaired("#tpUG0wGAY0123456789ABCDEFGHIJ__");
  EXPECT_EQ(out[5], 'F');
  EXPECT_TRUE(clean(std::string_view(out).substr(0, 10 + 15 + 2)));
}

TEST(Mutator, LeavesNothingToRepairAlone) {
  for (std::string s : {"", "#", "#tp", "#tpUG2wPTZ0", "no frame at all", "#XY0123456789"}) {
    std::string before = s;
    EXPECT_EQ(topfuzz::repair_frames(reinterpret_cast<std::uint8_t*>(s.data()), s.size()), 0u)
        << before;
    EXPECT_EQ(s, before);
  }
}

TEST(Mutator, LeavesAboutOneInEightUnrepaired) {
  int left = 0;
  const int n = 80000;
  for (int seed = 0; seed < n; ++seed)
    left += topfuzz::leave_unrepaired(static_cast<unsigned>(seed));
  EXPECT_GT(left, n / 8 - n / 80);
  EXPECT_LT(left, n / 8 + n / 80);
  // Deterministic from the seed.
  EXPECT_EQ(topfuzz::leave_unrepaired(12345), topfuzz::leave_unrepaired(12345));
}

TEST(Reference, AcceptsTheDocumentsExamples) {
  for (const char* s : {"#TPUG2wPTZ006A", "#tpUG6wGAYEF073288", "#TPMU2wERE!!30",
                        "#tpMU4rZOMFFB447", "#tpUM8wZFPFFB400320F", "#tpPM5rVSNM33265D"}) {
    auto f = topref::parse(s);
    ASSERT_TRUE(f.has_value()) << s;
    EXPECT_EQ(f->size, std::string_view(s).size()) << s;
  }
}

TEST(Reference, RejectsWhatTheDocumentsDoNotDefine) {
  for (const char* s : {
           "#TPUG6wGAYEF073288",   // SkyDroid erratum: checksum computed as #tp
           "#tpUG6wGAYEF0732 88",  // data longer than declared
           "#tpDU3rVER0105025A",   // lying length (field note)
           "#tpUG2wPTZ006a",       // checksum digits must be uppercase (every example)
           "#tpUg2wPTZ0073",       // address outside U M D E P G
           "#tpUG2xPTZ0074",       // control outside r/w
           "#tpUG2wPtz00AA",       // identifier not uppercase
           "#tpUG2wPTZ0",          // ends inside the frame
       })
    EXPECT_FALSE(topref::parse(s).has_value() &&
                 topref::parse(s)->size == std::string_view(s).size())
        << s;
}

TEST(Reference, DecodesTheDocumentsWorkedValues) {
  // Topotek: "#tpMU4rZOMFFB447; Z0Z1Z2Z3 = FFB4 -> -76".
  auto f = topref::parse("#tpMU4rZOMFFB447");
  ASSERT_TRUE(f);
  const topref::Layout* l = topref::find_layout("topotek", *f);
  ASSERT_NE(l, nullptr);
  auto v = topref::decode(*l, f->data);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].value, -76);
  // SkyDroid 3.3.1: "-50 deg is -5000 = 0xEC78"; speed hex.
  const std::string frame = top::with_checksum("#tpUG6wGAYEC7805");
  auto h = topref::parse(frame);
  ASSERT_TRUE(h);
  auto w = topref::decode(*topref::find_layout("skydroid", *h), h->data);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0].value, -5000);
  EXPECT_EQ(w[1].value, 5);
}

TEST(Dictionary, IsGeneratedFromTheCatalogInLibFuzzerSyntax) {
  std::ifstream in(std::string(TOPKIT_BINARY_DIR) + "/fuzz/top.dict");
  ASSERT_TRUE(in) << "fuzz/top.dict was not generated";
  std::string line, all;
  int entries = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    EXPECT_TRUE(dict_entry(line)) << line;
    ++entries;
    all += line + "\n";
  }
  EXPECT_GT(entries, 50);
  for (Dialect d : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& c : commands(d))
      EXPECT_NE(all.find("=\"" + std::string(c.ident) + "\""), std::string::npos) << c.ident;
  for (const char* h : {"#TP", "#tp", "#tP", "#Tp", "#PDP16TMP"})
    EXPECT_NE(all.find(std::string("=\"") + h + "\""), std::string::npos) << h;
}

// The capture targets check each JSON line with json_check.hpp instead of
// nlohmann::json::accept (the old check): it must reject everything
// nlohmann rejects, and accept what it accepts (else the targets would
// abort on good output).
namespace {

std::string json_verdicts(std::string_view text) {
  const topfuzz::Json v = topfuzz::json_check(text);
  const bool ours = v == topfuzz::Json::valid;
  const bool theirs = nlohmann::json::accept(text);
  if (v == topfuzz::Json::too_deep) return theirs ? "too deep, nlohmann accepts" : "";
  return ours == theirs ? ""
                        : std::string(ours ? "json_check accepts" : "json_check rejects") +
                              ", nlohmann " + (theirs ? "accepts" : "rejects");
}

}  // namespace

TEST(JsonCheck, AgreesWithNlohmannOnCraftedTexts) {
  const char* const cases[] = {"",
                               " ",
                               "{}",
                               "[]",
                               "{ }",
                               " [ ] ",
                               "null",
                               "true",
                               "false",
                               "nul",
                               "truex",
                               "[true,]",
                               "[,1]",
                               "{\"a\":1,}",
                               "{\"a\" 1}",
                               "{a:1}",
                               "{\"a\":1",
                               "[1 2]",
                               "\"x\"",
                               "\"x",
                               "'x'",
                               "0",
                               "-0",
                               "01",
                               "-",
                               "1.",
                               ".5",
                               "1e",
                               "1e+",
                               "1E-2",
                               "+1",
                               "-1.5e300",
                               "1e309",
                               "-1e309",
                               "1e-400",
                               "123456789012345678901234567890",
                               "0x10",
                               "NaN",
                               "Infinity",
                               "[1]x",
                               "{}{}",
                               "\"\\u0041\"",
                               "\"\\u00e9\"",
                               "\"\\uD83D\\uDE00\"",
                               "\"\\uD83D\"",
                               "\"\\uDE00\"",
                               "\"\\uD83D\\u0041\"",
                               "\"\\uD83Dx\"",
                               "\"\\u12\"",
                               "\"\\x41\"",
                               "\"\\a\"",
                               "\"\\/\\b\\f\\n\\r\\t\\\\\\\"\"",
                               "\"tab\there\"",
                               "\"nl\nhere\"",
                               "\"\xC3\xA9\"",
                               "\"\xC3\"",
                               "\"\xC0\xAF\"",
                               "\"\xE0\x80\xAF\"",
                               "\"\xED\xA0\x80\"",
                               "\"\xF4\x90\x80\x80\"",
                               "\"\xF0\x9F\x98\x80\"",
                               "\"\xFF\"",
                               "\"\x80\"",
                               "\xEF\xBB\xBF{}",
                               "\xEF\xBB{}",
                               "{}\xEF\xBB\xBF",
                               "\t{\r\n}\n",
                               "\f{}",
                               "{\"a\":[1,{\"b\":null}],\"c\":\"d\"}",
                               "[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]"};
  for (const char* c : cases) EXPECT_EQ(json_verdicts(c), "") << topfuzz::show(c);
  EXPECT_EQ(json_verdicts(std::string(400, '9')), "");
  EXPECT_EQ(json_verdicts("-" + std::string(308, '9') + ".5"), "");
  EXPECT_EQ(json_verdicts(std::string_view("\"a\0b\"", 5)), "");
  EXPECT_EQ(json_verdicts(std::string_view("[1]\0", 4)), "");
  EXPECT_EQ(json_verdicts(std::string_view("[1] \0x]", 7)), "");
  EXPECT_EQ(json_verdicts(std::string_view("[1,\0]", 5)), "");
  EXPECT_EQ(json_verdicts(std::string_view("\0", 1)), "");
  const std::string deep = std::string(300, '[') + std::string(300, ']');
  EXPECT_EQ(topfuzz::json_check(deep), topfuzz::Json::too_deep);
  EXPECT_EQ(json_verdicts(deep), "too deep, nlohmann accepts");
}

TEST(JsonCheck, AgreesWithNlohmannOnMutatedAnalyzerLikeLines) {
  // Lines shaped like topdump's JSON, each mutated many times (byte flips,
  // insertions and deletions of JSON-significant bytes), deterministically.
  const std::string seeds[] = {
      R"({"type":"frame","ts":1700000000.123456,"conv":1,"dir":"c2d","raw":"#TPUG2rGAY00","ok":true,"fields":[{"name":"yaw","value":-12.5}],"findings":[]})",
      R"({"type":"garbage","offset":17,"length":3,"preview":"\u0000\u00ab\\x","note":null})",
      R"({"type":"note","code":"unsupported_link","message":"link type 147 (\"USER0\") is not dissected","n":-0.0e-5})",
      R"(["\ud83d\ude00",1e10,-7,true,false,null,{"":[]}])"};
  static constexpr char kAlphabet[] =
      "{}[]\",:\\u0123456789abcdefABCDEF.eE+- \t\r\nntrfl\x00\x7F\x80\xBF\xC3\xE0\xED\xF0\xF4\xFF";
  const std::string_view alphabet(kAlphabet, sizeof kAlphabet - 1);
  std::uint64_t x = 0x9E3779B97F4A7C15ull;
  auto next = [&x] {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  int checked = 0;
  for (const std::string& seed : seeds) {
    for (int n = 0; n < 5000; ++n) {
      std::string s = seed;
      const int edits = 1 + static_cast<int>(next() % 3);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = next() % (s.size() + 1);
        const char c = alphabet[next() % alphabet.size()];
        switch (next() % 3) {
          case 0:
            if (at < s.size()) s[at] = c;
            break;
          case 1:
            s.insert(at, 1, c);
            break;
          default:
            if (at < s.size()) s.erase(at, 1);
        }
      }
      ASSERT_EQ(json_verdicts(s), "") << topfuzz::show(s, 400);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 20000);
}

TEST(JsonCheck, SamplesAboutOneInputInSixteenFromItsBytes) {
  int hits = 0;
  for (std::uint32_t i = 0; i < 16000; ++i) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&i);
    const bool s = topfuzz::sampled(p, sizeof i, 4);
    EXPECT_EQ(s, topfuzz::sampled(p, sizeof i, 4));
    hits += s;
  }
  EXPECT_GT(hits, 800);
  EXPECT_LT(hits, 1200);
}
