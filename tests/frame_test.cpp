#include "top/frame.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_util.hpp"
#include "top/detail/parse_paths.hpp"
#include "top/detail/text.hpp"

using namespace top;
using toptest::ExactBuffer;
using toptest::has_code;
using toptest::tmp_quirk_frame;

TEST(Checksum, AppendixExample) {
  // Both documents' appendix: "#TPUD2wAWB01" sums to 0x44.
  EXPECT_EQ(checksum("#TPUD2wAWB01"), 0x44);
  char b[2];
  put_hex2(0x44, b);
  EXPECT_EQ(std::string(b, 2), "44");
}

// The sum is taken eight bytes at a time: every length and every byte value
// (0xFF runs included, which carry furthest) against the plain loop, from
// an exact-size buffer so ASan sees any read past the end.
TEST(Checksum, EveryLengthAndByteAgreesWithTheByteLoop) {
  for (std::size_t n = 0; n <= 70; ++n)
    for (int fill : {0x00, 0x01, 0x7F, 0x80, 0xFF, -1}) {
      std::string s(n, '\0');
      for (std::size_t i = 0; i < n; ++i)
        s[i] = static_cast<char>(fill >= 0 ? fill : static_cast<int>((i * 131 + n * 7) & 0xFF));
      unsigned plain = 0;
      for (unsigned char c : s) plain += c;
      ExactBuffer buf(s);
      EXPECT_EQ(checksum(buf.view()), static_cast<std::uint8_t>(plain & 0xFF)) << n << " " << fill;
    }
}

// The character classes are a table: every byte against the documents'
// sets (addresses U M D E P G, SkyDroid 2 / Topotek 2; identifiers of
// uppercase letters and digits).
TEST(Chars, ClassesOfEveryByte) {
  for (int i = 0; i < 256; ++i) {
    const char c = static_cast<char>(i);
    const bool address = c == 'U' || c == 'M' || c == 'D' || c == 'E' || c == 'P' || c == 'G';
    const bool ident = (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    EXPECT_EQ(is_address(c), address) << i;
    EXPECT_EQ(is_ident_char(c), ident) << i;
    EXPECT_EQ(detail::char_is(c, detail::kClassLowerHex), c >= 'a' && c <= 'f') << i;
  }
}

TEST(Parse, ValidFixedFrame) {
  ExactBuffer buf("#TPUD2wAWB0144");
  ParseResult r = parse_frame(buf.view(), true);
  ASSERT_EQ(r.status, ParseStatus::frame);
  const Frame& f = r.frame;
  EXPECT_EQ(r.consumed, 14u);
  EXPECT_EQ(f.header, Header::fixed);
  EXPECT_EQ(f.src, 'U');
  EXPECT_EQ(f.dst, 'D');
  EXPECT_EQ(f.control, 'w');
  EXPECT_EQ(f.ident_view(), "AWB");
  EXPECT_EQ(f.data(), "01");
  EXPECT_EQ(f.declared_length, 2u);
  EXPECT_TRUE(f.checksum_ok);
  EXPECT_EQ(f.checksum, 0x44);
  EXPECT_EQ(f.checksum_text(), "44");
  EXPECT_TRUE(f.findings.empty());
  EXPECT_TRUE(f.ok());
}

// Every member of a parse result, as text, for comparing two parses (the
// messages left out when `messages` is false).
std::string describe_parse(const ParseResult& r, bool messages = true) {
  std::string s =
      std::to_string(static_cast<int>(r.status)) + " consumed " + std::to_string(r.consumed);
  if (r.status == ParseStatus::invalid)
    return s + " error " + std::string(to_string(r.error.code)) + "@" +
           std::to_string(r.error.offset) + " " + (messages ? r.error.message : "");
  if (r.status != ParseStatus::frame) return s;
  const Frame& f = r.frame;
  s += " header " + std::to_string(static_cast<int>(f.header)) + " " + f.src + f.dst +
       std::to_string(f.control) + std::string(f.ident_view()) + " declared " +
       std::to_string(f.declared_length) + " data " + std::to_string(f.data_offset) + "+" +
       std::to_string(f.data_length) + " checksum " + std::to_string(f.checksum) + "/" +
       std::to_string(f.expected_checksum) + (f.checksum_present ? " present" : "") +
       (f.checksum_ok ? " ok" : "") + " term " + std::to_string(f.terminator) + " raw " + f.raw;
  for (const Finding& x : f.findings)
    s += " | " + std::string(to_string(x.code)) + "/" + std::string(to_string(x.severity)) + "@" +
         std::to_string(x.offset) + " " + (messages ? x.message : "") + " " + std::string(x.quirk);
  return s;
}

// The one-pass path for clean frames gives what the general parse gives, on
// clean frames of every header and on each of them with one byte changed
// (header, address, length, control, identifier, data and checksum chars,
// case, CR/LF, '#', bytes outside ASCII) or cut short, with and without more
// bytes to come. One result is reused throughout, as the analyzer reuses it,
// so a fast parse after a general one (findings, error) must leave nothing
// of it behind. A parse without messages (ParseOptions::messages, as the
// stream decoder tries a '#' inside a frame) gives the same verdict, codes,
// severities and offsets, and no text at all.
TEST(Parse, FastPathAgreesWithTheGeneralParse) {
  std::vector<std::string> bases;
  for (Header h : {Header::fixed, Header::variable, Header::ext8, Header::ext16})
    for (std::string_view data : {"", "01", "0A1B2C3D4E5F", "ffff"})
      for (bool lower : {false, true}) {
        BuildSpec b;
        b.header = h;
        b.ident = "GAC";
        b.data = data;
        b.lowercase_checksum = lower;
        bases.push_back(build_frame(b));
      }
  for (std::size_t n = 0; n <= 15; ++n) {  // every one-digit length (raw copied in words)
    BuildSpec b;
    b.ident = "GAC";
    const std::string data = std::string("0123456789ABCDEF").substr(0, n);
    b.data = data;
    bases.push_back(build_frame(b));
  }
  bases.emplace_back("#TPUD2wAWB0144");
  bases.emplace_back("#PDP16TMP0000000000000000000000");
  static constexpr std::string_view kChars = "#TtPpUMDEPGXrw09AFafZ\r\n \x00\xff";
  ParseOptions quiet;
  quiet.messages = false;
  ParseResult reused, quiet_reused;
  std::size_t fast_frames = 0, compared = 0, texts = 0;
  auto compare = [&](const std::string& in) {
    ExactBuffer buf(in);
    for (bool at_end : {true, false}) {
      parse_frame(buf.view(), at_end, ParseOptions{}, reused);
      ParseResult slow;
      detail::parse_frame_general(buf.view(), at_end, ParseOptions{}, slow);
      ASSERT_EQ(describe_parse(reused), describe_parse(slow))
          << testing::PrintToString(in) << " " << at_end;
      parse_frame(buf.view(), at_end, quiet, quiet_reused);
      ASSERT_EQ(describe_parse(quiet_reused, false), describe_parse(slow, false))
          << testing::PrintToString(in) << " " << at_end;
      ASSERT_TRUE(quiet_reused.error.message.empty()) << testing::PrintToString(in);
      for (const Finding& x : quiet_reused.frame.findings)
        ASSERT_TRUE(x.message.empty()) << testing::PrintToString(in);
      texts += !slow.error.message.empty() || !slow.frame.findings.empty();
      fast_frames += reused.status == ParseStatus::frame && reused.frame.findings.empty();
      ++compared;
    }
  };
  for (const std::string& base : bases) {
    for (std::size_t n = 0; n <= base.size(); ++n) compare(base.substr(0, n));
    compare(base + "\r\n#TP");
    for (std::size_t i = 0; i < base.size(); ++i)
      for (char c : kChars) {
        std::string m = base;
        m[i] = c;
        compare(m);
      }
  }
  EXPECT_GT(compared, 5000u);
  EXPECT_GT(fast_frames, 100u);  // the one-pass path was taken
  EXPECT_GT(texts, 1000u);       // and many parses had a text to leave out
}

TEST(Parse, NeedMoreUntilComplete) {
  std::string s = "#tpUG6wGAYEF073288";
  for (std::size_t i = 1; i < s.size(); ++i) {
    ParseResult r = parse_frame(std::string_view(s).substr(0, i), false);
    EXPECT_EQ(r.status, ParseStatus::need_more) << "prefix " << i;
  }
  EXPECT_EQ(parse_frame(s, false).status, ParseStatus::frame);
}

// A need_more verdict says, once the header is read, how long the input must
// grow before the verdict can change (the stream decoder waits for that
// rather than parsing the header again for every byte of a serial link):
// every longer prefix below it is need_more too, and it is never past the
// first prefix with another verdict.
TEST(Parse, NeedMoreSaysHowManyBytesToWaitFor) {
  const std::string gay = "#tpUG6wGAYEF073288";
  const ParseResult r = parse_frame(std::string_view(gay).substr(0, 12), false);
  ASSERT_EQ(r.status, ParseStatus::need_more);
  EXPECT_EQ(r.consumed, gay.size());  // the data and the checksum
  std::size_t hinted = 0;
  for (std::string s : {gay, std::string("#tpUG6wGAYEF0732FF#TPUD2wCAP013E"),
                        std::string("#tPUD") + '\x14' + "wGAY" + std::string(20, '0') + "00",
                        std::string("#TpUD") + '\x00' + '\x03' + "ZOM0A0" + "00",
                        std::string("#tpDP16wTMP") + std::string(22, '0') + "00"}) {
    for (std::size_t i = 0; i < s.size(); ++i) {
      const std::string_view prefix = std::string_view(s).substr(0, i);
      const ParseResult p = parse_frame(prefix, false);
      if (p.status != ParseStatus::need_more || p.consumed == 0) continue;
      ++hinted;
      ASSERT_GT(p.consumed, i) << s << " prefix " << i;
      for (std::size_t j = i; j < p.consumed && j <= s.size(); ++j)
        ASSERT_EQ(parse_frame(std::string_view(s).substr(0, j), false).status,
                  ParseStatus::need_more)
            << s << " prefix " << j << " after a hint of " << p.consumed << " at " << i;
    }
  }
  EXPECT_GT(hinted, 20u);
}

TEST(Parse, BadChecksumCarriesExpected) {
  ParseResult r = parse_exact("#TPUD2wCAP0100");
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_FALSE(r.frame.checksum_ok);
  EXPECT_EQ(r.frame.expected_checksum, 0x3E);
  ASSERT_EQ(r.frame.findings.size(), 1u);
  const Finding& f = r.frame.findings[0];
  EXPECT_EQ(f.code, FindingCode::bad_checksum);
  EXPECT_EQ(f.severity, Severity::error);
  EXPECT_EQ(f.offset, 12u);
  EXPECT_NE(f.message.find("expected 3E"), std::string::npos) << f.message;
}

TEST(Parse, ChecksumMatchingAnotherHeaderCase) {
  // SkyDroid 3.3.1 and 3.3.5 examples: checksums computed with "#tp".
  for (const char* s : {"#TPUG6wGAYEF073288", "#TPUG8wGOT02800168D5"}) {
    ParseResult r = parse_exact(s);
    ASSERT_EQ(r.status, ParseStatus::frame) << s;
    EXPECT_TRUE(has_code(r.frame.findings, FindingCode::checksum_header_case)) << s;
    EXPECT_FALSE(has_code(r.frame.findings, FindingCode::bad_checksum)) << s;
    EXPECT_FALSE(r.frame.ok());
  }
}

TEST(Parse, LowercaseChecksumDigits) {
  ParseResult r = parse_exact("#tpUM2rZOM00a3");
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(r.frame.checksum_ok);
  EXPECT_TRUE(has_code(r.frame.findings, FindingCode::checksum_case));
  EXPECT_TRUE(r.frame.ok());
}

TEST(Parse, LyingLengthRecovered) {
  // DESIGN.md: a C12 answered #tpDU3rVER0105025A (length 3, six data chars).
  ParseResult r = parse_exact("#tpDU3rVER0105025A");
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(r.frame.checksum_ok);
  EXPECT_EQ(r.frame.data(), "010502");
  EXPECT_EQ(r.frame.declared_length, 3u);
  ASSERT_TRUE(has_code(r.frame.findings, FindingCode::length_mismatch));
  const auto& m = r.frame.findings[0].message;
  EXPECT_NE(m.find("declared length 3"), std::string::npos) << m;
  EXPECT_NE(m.find("6 data bytes"), std::string::npos) << m;
}

TEST(Parse, LyingLengthLongerThanData) {
  // Declared 8, six data chars, then the end of the datagram.
  ParseResult r = parse_exact("#tpDU8rVERV1.0.0" + std::string("7A"));
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(r.frame.checksum_ok);
  EXPECT_EQ(r.frame.data(), "V1.0.0");
  EXPECT_TRUE(has_code(r.frame.findings, FindingCode::length_mismatch));
}

TEST(Parse, NoChecksum) {
  ParseResult r = parse_exact("#TPUD2wCAP01");
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_FALSE(r.frame.checksum_present);
  EXPECT_TRUE(has_code(r.frame.findings, FindingCode::no_checksum));
  EXPECT_EQ(r.frame.expected_checksum, 0x3E);
}

struct Invalid {
  const char* bytes;
  FindingCode code;
  std::uint32_t offset;
};

class ParseInvalid : public ::testing::TestWithParam<Invalid> {};

TEST_P(ParseInvalid, NamesCodeAndOffset) {
  const Invalid& c = GetParam();
  ExactBuffer buf(c.bytes);
  ParseResult r = parse_frame(buf.view(), true);
  ASSERT_EQ(r.status, ParseStatus::invalid) << c.bytes;
  EXPECT_EQ(r.error.code, c.code) << c.bytes << ": " << r.error.message;
  EXPECT_EQ(r.error.offset, c.offset) << c.bytes;
  EXPECT_FALSE(r.error.message.empty());
}

INSTANTIATE_TEST_SUITE_P(Cases, ParseInvalid,
                         ::testing::Values(Invalid{"#XPUD2wCAP013E", FindingCode::bad_header, 1},
                                           Invalid{"#TXUD2wCAP013E", FindingCode::bad_header, 2},
                                           Invalid{"TPUD2wCAP013E", FindingCode::bad_header, 0},
                                           Invalid{"#TPXD2wCAP013E", FindingCode::bad_address, 3},
                                           Invalid{"#TPUx2wCAP013E", FindingCode::bad_address, 4},
                                           Invalid{"#TPUDZwCAP013E", FindingCode::bad_length_char,
                                                   5},
                                           Invalid{"#TPUD2xCAP013E", FindingCode::bad_control, 6},
                                           Invalid{"#TPUD2wCaP013E", FindingCode::bad_ident, 8},
                                           Invalid{"#TPUD2wCAP0", FindingCode::truncated, 11},
                                           Invalid{"#TP", FindingCode::truncated, 3}));

TEST(Parse, FrameTooLong) {
  ParseOptions o;
  o.max_data_length = 100;
  std::string s = "#tPUD";
  s += static_cast<char>(200);
  s += "wABC";
  ParseResult r = parse_frame(s, false, o);
  ASSERT_EQ(r.status, ParseStatus::invalid);
  EXPECT_EQ(r.error.code, FindingCode::frame_too_long);
}

TEST(Parse, TrailingBytesAndCrlf) {
  ParseResult r = parse_exact("#TPUD2wCAP013E\r\nxyz");
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(has_code(r.frame.findings, FindingCode::crlf));
  EXPECT_TRUE(has_code(r.frame.findings, FindingCode::trailing_bytes));
  EXPECT_EQ(r.frame.terminator, 2);
  ParseResult r2 = parse_exact("#TPUD2wCAP013E\r\n");
  EXPECT_FALSE(has_code(r2.frame.findings, FindingCode::trailing_bytes));
  EXPECT_TRUE(r2.frame.ok());
}

TEST(Parse, LowercaseLengthChar) {
  // IPV with 13 data chars, its length char written lowercase ("d")
  const std::string s = with_checksum("#tpUDdwIPV192.168.1.100");
  ParseResult r = parse_exact(s);
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(r.frame.checksum_ok);
  EXPECT_TRUE(has_code(r.frame.findings, FindingCode::lowercase_hex));
}

TEST(Parse, TmpQuirkDocumentedForm) {
  const std::string f = tmp_quirk_frame();
  ASSERT_EQ(f.size(), 9u + 22u + 2u);
  ParseResult r = parse_exact(f);
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_EQ(r.frame.header, Header::tmp_quirk);
  EXPECT_EQ(r.frame.ident_view(), "TMP");
  EXPECT_EQ(r.frame.src, 'D');
  EXPECT_EQ(r.frame.dst, 'P');
  EXPECT_EQ(r.frame.data_length, 22u);
  EXPECT_TRUE(r.frame.checksum_ok);
  ASSERT_TRUE(has_code(r.frame.findings, FindingCode::tmp_quirk));
  EXPECT_FALSE(r.frame.findings[0].quirk.empty());
  EXPECT_TRUE(r.frame.ok());
}

TEST(Parse, TmpQuirkTwoDigitLength) {
  ParseResult r = parse_exact(with_checksum("#tpDP16wTMP" + std::string(22, '0')));
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_EQ(r.frame.control, 'w');
  EXPECT_EQ(r.frame.declared_length, 0x16u);
  EXPECT_EQ(r.frame.data_offset, 11u);
  EXPECT_TRUE(has_code(r.frame.findings, FindingCode::tmp_quirk));
}

TEST(Parse, TwoDigitLengthOnAnotherIdent) {
  ParseResult r = parse_exact(with_checksum("#tpUD10wIPV" + std::string(16, '1')));
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(has_code(r.frame.findings, FindingCode::two_digit_length));
}

// Bytes as text: one escape for every tool, and the bytes of a vector's
// JSON string.
TEST(Text, EscapesRoundTripAndVectorStringsAreBytes) {
  std::string all;
  for (int c = 0; c < 256; ++c) all += static_cast<char>(c);
  std::string err;
  EXPECT_EQ(unescape(escape(all), err), all);
  EXPECT_EQ(escape("#\r\n\\\x7f"), "#\\r\\n\\\\\\x7F");
  EXPECT_EQ(hex_value('a'), 10);
  EXPECT_EQ(hex_value('F'), 15);
  EXPECT_EQ(hex_value('g'), -1);
  EXPECT_EQ(bytes_from_utf8("a\xc3\xbf\xc2\x80"), std::string("a\xff\x80"));
  EXPECT_FALSE(bytes_from_utf8("\xe2\x82\xac").has_value());  // U+20AC is no byte
  EXPECT_FALSE(bytes_from_utf8("\xc3").has_value());
  EXPECT_EQ(ascii_text("a\xe9"), "a\\xE9");
}

// One XML/HTML escape for topdump's report and topconf's reports: markup as
// entities, and the control bytes XML 1.0 forbids as escape() writes them
// (topdump's SVG wrote '.', topconf '\x0D' for a CR before).
TEST(Text, MarkupEscapeWritesControlBytesAsEscape) {
  EXPECT_EQ(markup_escape("<a href=\"x\">'&'</a>"),
            "&lt;a href=&quot;x&quot;&gt;'&amp;'&lt;/a&gt;");
  EXPECT_EQ(markup_escape(std::string("#TP\r\n\t\x01\x1f\x7f\xc3\xa9", 11)),
            std::string("#TP\\r\n\t\\x01\\x1F\x7f\xc3\xa9"));
  std::string all;
  for (int c = 0; c < 256; ++c) all += static_cast<char>(c);
  const std::string out = markup_escape(all);
  for (unsigned char c : out) EXPECT_TRUE(c >= 0x20 || c == '\t' || c == '\n') << int{c};
}

TEST(Addresses, EveryAddressHasItsDescriptionAndNothingElseDoes) {
  for (int c = 0; c < 256; ++c) {
    const char a = static_cast<char>(c);
    EXPECT_EQ(is_address(a), !describe_address(a).empty()) << c;
  }
  EXPECT_EQ(describe_address('U'), "UART/UDP client");
  EXPECT_EQ(describe_address('P'), "network client");
  EXPECT_EQ(describe_address('G'), "gimbal");
}

// Lengths that count bytes: the recorded field forms (the C12 palette, a
// range reply) are decoded as a quirk, info; a random wrong length is not.
TEST(Parse, LengthThatCountsBytesIsAQuirkOnlyInARecordedForm) {
  for (const char* body : {"#TPDU1rIMG01", "#TPDU2rSLR0018"}) {
    const ParseResult r = parse_exact(with_checksum(body));
    ASSERT_EQ(r.status, ParseStatus::frame) << body;
    EXPECT_EQ(r.frame.data_length, 2 * r.frame.declared_length) << body;
    EXPECT_TRUE(has_code(r.frame.findings, FindingCode::length_in_bytes)) << body;
    EXPECT_FALSE(has_code(r.frame.findings, FindingCode::length_mismatch)) << body;
    for (const Finding& f : r.frame.findings)
      if (f.code == FindingCode::length_in_bytes) {
        EXPECT_EQ(f.severity, Severity::info);
        EXPECT_EQ(f.quirk, "skydroid-length-in-bytes");
      }
  }
  const std::string sdr = with_checksum("#TPDU2rSLR0018");
  EXPECT_EQ(sdr, "#TPDU2rSLR0018BE");  // the station's own quote
  // Twice the length in a form no device is recorded with (a write, the
  // request's address order, another identifier): a length mismatch.
  for (const char* body : {"#TPDU1wIMG01", "#TPUD1rIMG01", "#TPDU1rVID01", "#tpDU3rVER010502"}) {
    const ParseResult r = parse_exact(with_checksum(body));
    ASSERT_EQ(r.status, ParseStatus::frame) << body;
    EXPECT_TRUE(has_code(r.frame.findings, FindingCode::length_mismatch)) << body;
    EXPECT_FALSE(has_code(r.frame.findings, FindingCode::length_in_bytes)) << body;
  }
}

// The C10 Pro tool's double-checksum frames: the second checksum is the
// frame's (a quirk, info), not two garbage or trailing bytes; a wrong
// second checksum still is trailing bytes.
TEST(Parse, DoubleChecksumIsTheFramesNotGarbage) {
  for (const char* raw : {"#TPUG2wPTZ056FEB", "#TPUG2wPTZ016BE3", "#TPUG2wPTZ026CE5"}) {
    const ParseResult r = parse_exact(raw);
    ASSERT_EQ(r.status, ParseStatus::frame) << raw;
    EXPECT_TRUE(r.frame.ok()) << raw;
    EXPECT_EQ(r.frame.data(), std::string_view(raw).substr(10, 2));
    EXPECT_TRUE(has_code(r.frame.findings, FindingCode::double_checksum)) << raw;
    EXPECT_FALSE(has_code(r.frame.findings, FindingCode::trailing_bytes)) << raw;
    // Its bytes are all it consumed, the second checksum too (they were two
    // short, and the stream decoder's items then missed two bytes).
    EXPECT_EQ(r.frame.raw, raw);
    EXPECT_EQ(r.consumed, r.frame.raw.size()) << raw;
    // In a stream of frames: the next frame starts right after it.
    const std::string two = std::string(raw) + "#TPUD2wCAP013E";
    const ParseResult first = parse_frame(two, false);
    ASSERT_EQ(first.status, ParseStatus::frame);
    EXPECT_EQ(first.consumed, 16u);
  }
  const ParseResult wrong = parse_exact("#TPUG2wPTZ056FEC");
  ASSERT_EQ(wrong.status, ParseStatus::frame);
  EXPECT_FALSE(has_code(wrong.frame.findings, FindingCode::double_checksum));
  EXPECT_TRUE(has_code(wrong.frame.findings, FindingCode::trailing_bytes));
}
