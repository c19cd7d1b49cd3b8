// Pairing (session/pairing.hpp) driven directly: requests added, responses
// matched, requests expired.
#include "session/pairing.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace topdump {
namespace {

constexpr int kClient = 0, kDevice = 1;  // the directions

// A request of frame `n` at `ts` (microseconds), sent by the client to G.
void add(Pairing& p, std::uint64_t n, std::int64_t ts, std::string_view ident, char control,
         std::string_view data, char dst = 'G', int dir = kClient,
         const top::CommandSpec* command = nullptr) {
  p.add([&](Pending& x) {
    x.ts = ts;
    x.n = n;
    x.pos = Position{n, 0, 0};
    std::memcpy(x.ident, ident.data(), 3);
    x.control = control;
    x.src = 'U';
    x.dst = dst;
    x.data.assign(data);
    x.dir = dir;
    x.cause = Cause::none;
    x.command = command;
    x.at = nullptr;
  });
}

// A real Topotek camera takes a TRC write silently and answers the TRC read
// sent right after it (PixEagle bench, 20260917T045408Z-tracking-ready
// 04:54:10.483447: #TPPD2wTRC024F, #TPPD2rTRC0048, then #TPDP2rTRC0149):
// the read's reply answers the read, even when its data is the write's
// (cancel to ready, TRC 01, then a read answered 01).
TEST(Pairing, AReplyAnswersARequestOfItsOwnControlFirst) {
  Pairing p;
  add(p, 1, 0, "TRC", 'w', "01", 'D');
  add(p, 2, 10, "TRC", 'r', "00", 'D');
  auto m = p.match("TRC", "01", 'r', 'D', kDevice, false);
  ASSERT_TRUE(m);
  EXPECT_EQ(p[m->index].n, 2u);
  EXPECT_FALSE(m->echoed);
  p.answer(m->index);
  // with no read pending, an echo of the write still answers it
  m = p.match("TRC", "01", 'w', 'D', kDevice, false);
  ASSERT_TRUE(m);
  EXPECT_EQ(p[m->index].n, 1u);
  EXPECT_TRUE(m->echoed);
  // and a reply of the other control takes what is left (a device that
  // answers a read in a write's form)
  p.answer(m->index);
  add(p, 3, 20, "TRC", 'r', "00", 'D');
  m = p.match("TRC", "02", 'w', 'D', kDevice, false);
  ASSERT_TRUE(m);
  EXPECT_EQ(p[m->index].n, 3u);
}

// A write its device takes silently (Topotek TRC) waits only for an echo:
// a read's reply never answers it, even with no read pending (topsim's
// sip answered a TRC read, and its copy to 9004 went to the TRC write).
TEST(Pairing, ASilentWriteTakesOnlyAnEcho) {
  Pairing p;
  // Topotek TRC: a write the document gives no reply form
  add(p, 1, 0, "TRC", 'w', "02", 'D', kClient, top::find_command(top::Dialect::topotek, "TRC"));
  EXPECT_FALSE(p.match("TRC", "01", 'r', 'D', kDevice, false));
  auto m = p.match("TRC", "02", 'w', 'D', kDevice, false);
  ASSERT_TRUE(m);
  EXPECT_TRUE(m->echoed);
}

TEST(Pairing, ResponseMatchesARequestOfItsIdentifierSentTheOtherWay) {
  Pairing p;
  add(p, 1, 0, "VER", 'r', "");
  add(p, 2, 10, "GAC", 'r', "");
  EXPECT_EQ(p.maybe_pending("VER", kClient), 1u);
  EXPECT_TRUE(p.waiting("VER", kClient));
  EXPECT_FALSE(p.waiting("VER", kDevice));
  // a VER from the client's side answers nothing
  EXPECT_FALSE(p.match("VER", "0105", 'r', 'U', kClient, false));
  // one from the device answers frame 1
  auto m = p.match("VER", "0105", 'r', 'G', kDevice, false);
  ASSERT_TRUE(m);
  EXPECT_EQ(p[m->index].n, 1u);
  EXPECT_FALSE(m->echoed);
  p.answer(m->index);
  EXPECT_EQ(p.size(), 1u);
  EXPECT_FALSE(p.waiting("VER", kClient));
  EXPECT_FALSE(p.match("VER", "0105", 'r', 'G', kDevice, false));  // answered once
  EXPECT_FALSE(p.match("GAY", "", 'w', 'G', kDevice, false));      // never asked
}

TEST(Pairing, PrefersTheRequestItEchoesThenTheNewest) {
  Pairing p;
  add(p, 1, 0, "GAY", 'w', "0100");
  add(p, 2, 10, "GAY", 'w', "0200");
  add(p, 3, 20, "GAY", 'w', "0300");
  // the echo of frame 1's data pairs with frame 1, though newer ones wait
  auto m = p.match("GAY", "0100", 'w', 'G', kDevice, false);
  ASSERT_TRUE(m);
  EXPECT_EQ(p[m->index].n, 1u);
  EXPECT_TRUE(m->echoed);
  // a reply that echoes none pairs with the newest
  m = p.match("GAY", "0999", 'w', 'G', kDevice, false);
  ASSERT_TRUE(m);
  EXPECT_EQ(p[m->index].n, 3u);
  EXPECT_FALSE(m->echoed);
}

TEST(Pairing, EreAnswersTheNewestRequestToTheDeviceItSpeaksFor) {
  Pairing p;
  add(p, 1, 0, "GAY", 'w', "0100", 'G');
  add(p, 2, 10, "VER", 'r', "", 'D');
  add(p, 3, 20, "PTZ", 'w', "05", 'G');
  auto m = p.match("ERE", "!!", 'w', 'G', kDevice, true);
  ASSERT_TRUE(m);
  EXPECT_EQ(p[m->index].n, 3u);
  m = p.match("ERE", "!!", 'w', 'D', kDevice, true);
  ASSERT_TRUE(m);
  EXPECT_EQ(p[m->index].n, 2u);
  EXPECT_FALSE(p.match("ERE", "!!", 'w', 'M', kDevice, true));
}

TEST(Pairing, RequestsPastTheTimeoutAreUnansweredOldestFirst) {
  Pairing p;
  add(p, 1, 0, "VER", 'r', "");
  add(p, 2, 1'500'000, "GAC", 'r', "");
  EXPECT_EQ(p.oldest_ts(), 0);
  std::vector<std::uint64_t> unanswered;
  auto note = [&](const Pending& x) { unanswered.push_back(x.n); };
  p.expire(2'000'000, 2'000'000, note);  // exactly the timeout: still waits
  EXPECT_TRUE(unanswered.empty());
  p.expire(2'500'000, 2'000'000, note);
  EXPECT_EQ(unanswered, (std::vector<std::uint64_t>{1}));
  EXPECT_EQ(p.oldest_ts(), 1'500'000);
  p.expire(kNoTime, 2'000'000, note);  // an untimed frame expires nothing
  p.expire(9'000'000, 2'000'000, note);
  EXPECT_EQ(unanswered, (std::vector<std::uint64_t>{1, 2}));
  EXPECT_TRUE(p.empty());
  EXPECT_EQ(p.oldest_ts(), kNoTime);
}

TEST(Pairing, CopyOfAnAnsweredRequestIsRecognisedWithinTheWindow) {
  Pairing p;
  add(p, 1, 1'000'000, "GAY", 'w', "0100");
  p.answer(p.match("GAY", "0100", 'w', 'G', kDevice, false)->index);
  add(p, 2, 1'030'000, "GAY", 'w', "0100");  // a copy 30 ms later
  add(p, 3, 1'060'000, "GAY", 'w', "0200");  // other data
  add(p, 4, 1'500'000, "GAY", 'w', "0100");  // the same, but 500 ms later
  EXPECT_TRUE(p.copy_of_answered(p[0], 100'000));
  EXPECT_FALSE(p.copy_of_answered(p[1], 100'000));
  EXPECT_FALSE(p.copy_of_answered(p[2], 100'000));
  EXPECT_FALSE(p.copy_of_answered(p[0], -1));  // no window
}

TEST(Pairing, PopOldestKeepsTheCountsInStep) {
  Pairing p;
  for (std::uint64_t n = 1; n <= 3; ++n) add(p, n, static_cast<std::int64_t>(n), "VER", 'r', "");
  EXPECT_EQ(p.maybe_pending("VER", kClient), 3u);
  p.pop_oldest();
  EXPECT_EQ(p.maybe_pending("VER", kClient), 2u);
  EXPECT_EQ(p.oldest().n, 2u);
  EXPECT_EQ(p.oldest_ts(), 2);
}

}  // namespace
}  // namespace topdump
