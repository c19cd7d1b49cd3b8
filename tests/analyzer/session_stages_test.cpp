// The session's stages on their own (issue 48): the conversation table
// (session/conversation_table.hpp), the counting stage and the latency
// stage (session/counters.hpp), fed what the session feeds them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "session/conversation_table.hpp"
#include "session/counters.hpp"
#include "top/frame.hpp"

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

// Past kExact samples the quantiles come from the 1% buckets, which are
// filled only then, the exact samples counted in first: the median of
// 1..5000 us is the bucket of 2500 us, not of the later samples alone.
TEST(Latency, QuantilesPastTheExactSamplesCountEverySample) {
  Latency l;
  for (std::int64_t us = 1; us <= 4096; ++us) l.add(us);
  EXPECT_EQ(l.quantile(0.5), 2048) << "exact up to 4096 samples";
  for (std::int64_t us = 4097; us <= 5000; ++us) l.add(us);
  EXPECT_EQ(l.count(), 5000u);
  EXPECT_EQ(l.min(), 1);
  EXPECT_EQ(l.max(), 5000);
  // the bucket of 2500 us: 1.01^b, b its 1% bucket
  const auto b = static_cast<double>(Latency::bucket(2500));
  EXPECT_EQ(l.quantile(0.5), std::llround(std::pow(1.01, b)));
  EXPECT_NEAR(static_cast<double>(l.quantile(0.5)), 2500, 25);
  EXPECT_NEAR(static_cast<double>(l.quantile(0.1)), 500, 5);
}

const Endpoint kCamera = Endpoint::ipv4(0xC0A89064, 9003);  // 192.168.144.100:9003
const Endpoint kClientEnd = Endpoint::ipv4(0xC0A8900A, 40000);
TableOptions topotek() { return TableOptions{top::Dialect::topotek, top::Model::sip, 1 << 20}; }

TEST(ConversationTable, OnePerPairOfEndsEitherWay) {
  ConversationTable t(TableOptions{});
  const Route* r = nullptr;
  EXPECT_EQ(t.find(Transport::udp, kClientEnd, kCamera, r), nullptr);
  Conversation& c = t.add(Transport::udp, kClientEnd, kCamera, r);
  EXPECT_EQ(c.id, 1u);
  EXPECT_EQ(r->dir, 0);
  EXPECT_EQ(c.device_dir, 1) << "the camera's end is on a device port";
  const Route* back = nullptr;
  EXPECT_EQ(t.find(Transport::udp, kCamera, kClientEnd, back), &c);
  EXPECT_EQ(back->dir, 1);
  EXPECT_EQ(back->from, kCamera.text());
  EXPECT_EQ(t.find(Transport::tcp, kClientEnd, kCamera, r), nullptr) << "another transport";
  Conversation& other = t.add(Transport::tcp, kClientEnd, kCamera, r);
  EXPECT_EQ(other.id, 2u);
  EXPECT_EQ(t.size(), 2u);
  // the least recently used goes first
  EXPECT_EQ(&t.least_recent(), &c);
  t.remove(c);
  EXPECT_EQ(t.size(), 1u);
  EXPECT_EQ(t.find(Transport::udp, kCamera, kClientEnd, r), nullptr) << "not from the cache either";
  std::vector<std::uint64_t> ids;
  for (const Conversation* x : t.by_id()) ids.push_back(x->id);
  EXPECT_EQ(ids, std::vector<std::uint64_t>{2});
}

TEST(ConversationTable, ATopotekCameraTakesEveryPairBetweenTheTwoHosts) {
  // a real Topotek camera answers from an ephemeral port, to any port of
  // the client's host (docs/FIELD.md: ephemeral-reply-port, fan-out)
  ConversationTable t(topotek());
  const Route* r = nullptr;
  Conversation& c = t.add(Transport::udp, kClientEnd, kCamera, r);
  ASSERT_TRUE(c.link);
  const Endpoint reply_port = Endpoint::ipv4(0xC0A89064, 51234);
  const Endpoint listener = Endpoint::ipv4(0xC0A8900A, 9004);
  EXPECT_EQ(t.find(Transport::udp, reply_port, listener, r), &c);
  EXPECT_EQ(r->dir, 1) << "the device's direction";
  EXPECT_EQ(r->from, reply_port.text());
  EXPECT_EQ(t.find(Transport::udp, reply_port, listener, r), &c) << "found again";
  const Endpoint stranger = Endpoint::ipv4(0xC0A8900B, 9004);
  EXPECT_EQ(t.find(Transport::udp, reply_port, stranger, r), nullptr) << "another host";
  Endpoint to;
  c.dir[1].sent_frame = true;
  c.dir[1].last_frame_ts = 5;
  EXPECT_EQ(t.answered_elsewhere(c, c.dir[0], 0, to), nullptr) << "one conversation";
  t.clear();
  EXPECT_EQ(t.size(), 0u);
}

// answered_elsewhere() looks through the conversations of the request's
// destination end, the first made first; that index is built at its first
// call (few captures ask), then kept as conversations come and go.
TEST(ConversationTable, AnsweredElsewhereSeesConversationsMadeBeforeAndAfterItsFirstCall) {
  ConversationTable t(TableOptions{});
  const Route* r = nullptr;
  Conversation& asked = t.add(Transport::udp, kClientEnd, kCamera, r);
  const Endpoint other_port = Endpoint::ipv4(0xC0A8900A, 40001);
  const Endpoint third_port = Endpoint::ipv4(0xC0A8900A, 40002);
  Conversation& early = t.add(Transport::udp, kCamera, other_port, r);
  Endpoint to;
  EXPECT_EQ(t.answered_elsewhere(asked, asked.dir[0], 0, to), nullptr) << "it sent nothing";
  early.dir[0].sent_frame = true;
  early.dir[0].last_frame_ts = 10;
  EXPECT_EQ(t.answered_elsewhere(asked, asked.dir[0], 0, to), &early);
  EXPECT_EQ(to, other_port);
  EXPECT_EQ(t.answered_elsewhere(asked, asked.dir[0], 11, to), nullptr) << "before `after`";
  Conversation& late = t.add(Transport::udp, kCamera, third_port, r);
  late.dir[0].sent_frame = true;
  late.dir[0].last_frame_ts = 20;
  EXPECT_EQ(t.answered_elsewhere(asked, asked.dir[0], 0, to), &early) << "the first made first";
  t.remove(early);
  EXPECT_EQ(t.answered_elsewhere(asked, asked.dir[0], 0, to), &late) << "made after the first call";
  EXPECT_EQ(to, third_port);
  t.clear();
  Conversation& again = t.add(Transport::udp, kClientEnd, kCamera, r);
  Conversation& other = t.add(Transport::udp, kCamera, other_port, r);
  other.dir[0].sent_frame = true;
  other.dir[0].last_frame_ts = 30;
  EXPECT_EQ(t.answered_elsewhere(again, again.dir[0], 0, to), &other) << "after clear()";
}

// A direction's decoder is made at its first bytes; until then it is one
// that was fed nothing.
TEST(LazyDecoder, UntilFedItIsADecoderFedNothing) {
  LazyDecoder d;
  top::StreamItem it;
  d.flush();
  d.finish();
  d.reset();
  EXPECT_EQ(d.fed(), 0u);
  EXPECT_FALSE(d.next(it));
  const std::string frame = top::with_checksum("#TPUG2wPTZ05");
  d.feed(frame);
  d.finish();
  EXPECT_EQ(d.fed(), frame.size());
  ASSERT_TRUE(d.next(it));
  EXPECT_EQ(it.kind, top::ItemKind::frame);
  EXPECT_FALSE(d.next(it));
}

}  // namespace
}  // namespace topdump
