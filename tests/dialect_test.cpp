#include "top/dialect.hpp"

#include <gtest/gtest.h>

#include <set>

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

// The ports table: each port once per transport, each with its source, and
// what the simulator and the runner read from it.
TEST(Dialect, KnownPortsSayWhereEachIsWritten) {
  std::set<std::pair<std::uint16_t, bool>> seen;
  for (const PortSpec& p : known_ports()) {
    EXPECT_TRUE(seen.insert({p.port, p.tcp}).second) << p.port;
    EXPECT_FALSE(p.source.empty()) << p.port;
    EXPECT_NE(p.dialect, Dialect::unknown);
    EXPECT_EQ(p.served & ~p.models, 0) << p.port;  // served only by models that use it
    EXPECT_EQ(dialect_from_port(p.port), p.dialect);
    EXPECT_TRUE(is_top_port(p.port));
  }
  EXPECT_EQ(seen.size(), 6u);
  for (Model m : all_models()) {
    const PortSpec* d = default_port(m);
    ASSERT_NE(d, nullptr) << to_string(m);
    EXPECT_EQ(d->dialect, dialect_of(m));
  }
  EXPECT_EQ(default_port(Model::unknown), nullptr);
  EXPECT_EQ(default_port(Model::c12)->port, 5000);
  EXPECT_FALSE(default_port(Model::c12)->tcp);
  EXPECT_EQ(default_port(Model::c20)->port, 5000);
  EXPECT_TRUE(default_port(Model::c20)->tcp);
  EXPECT_EQ(default_port(Model::sip)->port, 9003);
  EXPECT_EQ(client_port(Model::sip), 9004);
  EXPECT_EQ(client_port(Model::c10), 0);
  EXPECT_FALSE(is_top_port(5001));
}
