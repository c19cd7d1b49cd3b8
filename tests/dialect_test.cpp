#include "top/dialect.hpp"

#include <gtest/gtest.h>

using namespace top;

namespace {
Frame parse(std::string_view s) { return parse_exact(s).frame; }
}  // namespace

TEST(Dialect, Ports) {
  EXPECT_EQ(dialect_from_port(5000), Dialect::skydroid);
  EXPECT_EQ(dialect_from_port(9002), Dialect::skydroid);
  EXPECT_EQ(dialect_from_port(12580), Dialect::skydroid);
  EXPECT_EQ(dialect_from_port(9003), Dialect::topotek);
  EXPECT_EQ(dialect_from_port(9004), Dialect::topotek);
  EXPECT_EQ(dialect_from_port(80), Dialect::unknown);
  EXPECT_TRUE(is_top_port(9004));
  EXPECT_FALSE(is_top_port(53));
}

TEST(Dialect, FromFrames) {
  EXPECT_EQ(dialect_from_frame(parse("#tpPM2wZMC0097")), Dialect::topotek);   // P address
  EXPECT_EQ(dialect_from_frame(parse("#TPUG2rGIC003A")), Dialect::topotek);   // Topotek only
  EXPECT_EQ(dialect_from_frame(parse("#TPUD2rTSM0058")), Dialect::skydroid);  // SkyDroid only
  EXPECT_EQ(dialect_from_frame(parse("#TPUG2wPTZ006A")), Dialect::unknown);   // both
}

TEST(Dialect, DetectorVotesPortsAndOverride) {
  DialectDetector d;
  EXPECT_EQ(d.current(), Dialect::unknown);
  d.observe_port(9003);
  EXPECT_EQ(d.current(), Dialect::topotek);
  d.observe(parse("#TPUD2rTSM0058"));
  EXPECT_EQ(d.current(), Dialect::skydroid);  // frames outweigh the port
  d.force(Dialect::topotek);
  EXPECT_EQ(d.current(), Dialect::topotek);
}
