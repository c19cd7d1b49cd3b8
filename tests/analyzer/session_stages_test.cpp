// The session's stages on their own (issue 48): the counting stage and the
// latency stage (session/counters.hpp), fed what the session feeds them.
#include <gtest/gtest.h>

#include "session/counters.hpp"

namespace topdump {
namespace {

TEST(Counters, FramesPerIdentifierAndFindingsPerCode) {
  Counters c;
  c.ident("GAC");
  c.ident("GAC");
  c.ident("ZZ9");  // the last slot of the last page
  c.ident("AAA");  // the first slot
  const char odd[3] = {'g', '\x01', '#'};
  c.ident(odd);  // not [0-9A-Z]: counted apart
  c.finding(top::FindingCode::bad_checksum);
  c.note(ACode::unanswered);
  c.note(ACode::unanswered);
  EXPECT_EQ(c.notes(ACode::unanswered), 2u);
  EXPECT_EQ(c.notes(ACode::unsolicited), 0u);
  Stats s;
  s.per_ident["stale"] = 9;  // materialize replaces what was there
  c.materialize(s);
  EXPECT_EQ(s.per_ident.size(), 4u);
  EXPECT_EQ(s.per_ident["GAC"], 2u);
  EXPECT_EQ(s.per_ident["ZZ9"], 1u);
  EXPECT_EQ(s.per_ident["AAA"], 1u);
  EXPECT_EQ(s.per_ident[unpack_ident(pack_ident(std::string_view(odd, 3)))], 1u);
  EXPECT_EQ(s.per_code["bad-checksum"], 1u);
  EXPECT_EQ(s.per_code["unanswered"], 2u);
  EXPECT_EQ(s.per_code.size(), 2u);
}

TEST(Counters, AnIdentifierRoundTripsThroughItsKey) {
  EXPECT_EQ(unpack_ident(pack_ident("VER")), "VER");
  EXPECT_EQ(pack_ident("VE"), pack_ident(std::string_view("VE\0", 3)));
}

TEST(LatencyTable, OneHistogramPerIdentifierWhateverTheOrder) {
  LatencyTable t;
  // more identifiers than hint slots collide in: each keeps its own
  for (std::uint32_t round = 0; round < 3; ++round)
    for (std::uint32_t k = 1; k <= 200; ++k) t.of(k * 7919).add(static_cast<std::int64_t>(k));
  std::map<std::string, Latency> out;
  t.materialize(out);
  EXPECT_EQ(out.size(), 200u) << "keys whose text is equal would merge; these are distinct";
  const Latency& a = t.of(7919);
  EXPECT_EQ(a.count(), 3u);
  EXPECT_EQ(a.min(), 1);
  EXPECT_EQ(t.of(200 * 7919).max(), 200);
  EXPECT_EQ(t.of(pack_ident("GAC")).count(), 0u) << "a new identifier starts empty";
}

}  // namespace
}  // namespace topdump
