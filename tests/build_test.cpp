// The frame builder: headers, lengths, checksums, and the deliberate
// malformations BuildSpec makes (top/frame.hpp).
#include <gtest/gtest.h>

#include <string>

#include "test_util.hpp"
#include "top/frame.hpp"

using namespace top;
using toptest::tmp_quirk_frame;

// Into a buffer: what was there is replaced (a checksum of the old contents
// and the new frame together would be wrong), whatever its length.
TEST(Build, IntoABufferReplacesItsContents) {
  std::string out = std::string(300, 'x');
  build_frame({.header = Header::fixed, .dst = 'D', .ident = "AWB", .data = "01"}, out);
  EXPECT_EQ(out, "#TPUD2wAWB0144");
  build_frame({.ident = "GAY", .data = "EF0732"}, out);
  EXPECT_EQ(out, "#tpUG6wGAYEF073288");
}

TEST(Build, HeadersAndLengths) {
  // src U and control w are BuildSpec's defaults
  EXPECT_EQ(build_frame({.header = Header::fixed, .dst = 'D', .ident = "AWB", .data = "01"}),
            "#TPUD2wAWB0144");
  EXPECT_EQ(build_frame({.ident = "GAY", .data = "EF0732"}), "#tpUG6wGAYEF073288");
  EXPECT_EQ(
      build_frame(
          {.dst = 'M', .control = 'r', .ident = "ZOM", .data = "00", .lowercase_checksum = true}),
      "#tpUM2rZOM00a3");
  // Data too long for the header asked for: the next header that holds it,
  // its length in raw bytes (ext16 has no control byte).
  struct Extended {
    std::string data;
    Header asked, got;
    std::string_view prefix, length;
    char control;
  };
  for (const Extended& x :
       {Extended{std::string(40, 'x'), Header::variable, Header::ext8, "#tP", "\x28", 'w'},
        Extended{std::string(300, '#'), Header::ext8, Header::ext16, "#Tp", "\x01\x2C", 0}}) {
    const std::string f = build_frame({.header = x.asked,
                                       .src = 'P',
                                       .dst = 'D',
                                       .control = 'w',
                                       .ident = "ABC",
                                       .data = x.data});
    EXPECT_EQ(f.substr(0, 3), x.prefix);
    EXPECT_EQ(f.substr(5, x.length.size()), x.length);
    ParseResult r = parse_exact(f);
    ASSERT_EQ(r.status, ParseStatus::frame);
    EXPECT_EQ(r.frame.header, x.got);
    EXPECT_EQ(r.frame.control, x.control);
    EXPECT_EQ(r.frame.data(), x.data);
    EXPECT_TRUE(r.frame.checksum_ok);
  }
}

// One helper appends the checksum (the fuzz seeds, the matrices, the faults
// and the device used to write it each).
TEST(Frame, WithChecksumAppendsTheSum) {
  EXPECT_EQ(with_checksum("#TPUG2wGAA01"), "#TPUG2wGAA0136");
  const std::string f = with_checksum("#tpUG6wGAYEF0732");
  const ParseResult r = parse_exact(f);
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(r.frame.checksum_ok);
}

// BuildSpec's deliberate malformations reproduce what real senders send.
TEST(Build, DeclaredLengthThatLiesIsTheC12VersionReply) {
  BuildSpec b;
  b.src = 'D';
  b.dst = 'U';
  b.control = 'r';
  b.ident = "VER";
  b.data = "010502";
  b.declared_length = 3;
  const std::string f = build_frame(b);
  EXPECT_EQ(f, "#tpDU3rVER0105025A");  // DESIGN.md, "Lengths that lie"
  const ParseResult r = parse_exact(f);
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(r.frame.has(FindingCode::length_mismatch));
  EXPECT_EQ(r.frame.data(), "010502");
}

TEST(Build, ChecksumOverAnotherHeaderIsTheGayExample) {
  BuildSpec b;
  b.header = Header::fixed;
  b.ident = "GAY";
  b.data = "EF0732";
  b.checksum_header = Header::variable;
  const std::string f = build_frame(b);
  EXPECT_EQ(f, "#TPUG6wGAYEF073288");  // SkyDroid 3.3.1's example
  const ParseResult r = parse_exact(f);
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(r.frame.has(FindingCode::checksum_header_case));
  b.checksum_header = Header::fixed;  // the header written: no malformation
  EXPECT_TRUE(parse_exact(build_frame(b)).frame.ok());
}

// The malformations topconf's fuzz cases and matrices send, each found by
// the parser as what it is.
TEST(Build, WrongMissingChecksumAndAOneDigitLengthPast15) {
  BuildSpec b;
  b.header = Header::fixed;
  b.ident = "PTZ";
  b.data = "05";
  b.checksum = 0x70;  // the sum is 0x6F
  EXPECT_EQ(build_frame(b), "#TPUG2wPTZ0570");
  EXPECT_TRUE(parse_exact(build_frame(b)).frame.has(FindingCode::bad_checksum));
  b.checksum.reset();
  b.omit_checksum = true;
  EXPECT_EQ(build_frame(b), "#TPUG2wPTZ05");
  EXPECT_TRUE(parse_exact(build_frame(b)).frame.has(FindingCode::no_checksum));
  b.omit_checksum = false;
  const std::string zeros(40, '0');
  b.header = Header::variable;
  b.data = zeros;
  b.keep_header = true;
  b.declared_length = 0xF;
  const std::string f = build_frame(b);
  EXPECT_EQ(f.substr(0, 11), "#tpUGFwPTZ0");
  EXPECT_EQ(f.size(), 11u + 40 - 1 + 2);  // the prefix, the data, the checksum
  b.keep_header = false;
  EXPECT_EQ(build_frame(b).substr(0, 3), "#tP");
}

TEST(Build, TwoDigitLengthIsTheTmpFirmwareForm) {
  BuildSpec b;
  b.src = 'D';
  b.dst = 'P';
  b.ident = "TMP";
  const std::string data = "0100200300400500600700";
  b.data = data;
  b.two_digit_length = true;
  const std::string f = build_frame(b);
  EXPECT_EQ(f.substr(0, 11), "#tpDP16wTMP");
  const ParseResult r = parse_exact(f);
  ASSERT_EQ(r.status, ParseStatus::frame);
  EXPECT_TRUE(r.frame.has(FindingCode::tmp_quirk));
  EXPECT_EQ(r.frame.data(), data);
}
