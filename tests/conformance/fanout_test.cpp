// Where topsim's datagrams go on the client's host (sim/fanout.hpp): the
// real Topotek camera's routes, replayed on the asking ports of its PixEagle
// bench sessions (the evidence of top::TraitKind::fan_out and
// duplicate_to_client_port; captures/sip-bench/<session>.pcap), and the
// document's.
#include "sim/fanout.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "sim/device.hpp"
#include "top/device.hpp"
#include "top/dialect.hpp"

namespace {

using Ports = std::vector<std::uint16_t>;
using topsim::Fanout;
using topsim::UdpTraits;

constexpr std::uint16_t kClient = 9004;

// The routes of each reply to the requests of `askers`, in order.
std::vector<Ports> replay(Fanout f, const Ports& askers) {
  std::vector<Ports> out;
  for (std::uint16_t p : askers) out.push_back(f.request(p));
  return out;
}

TEST(Fanout, TheDefaultSipHasTheRealCamerasRoutes) {
  // The default sip's traits are the field's (top::traits()), and its
  // client port the port table's.
  const topsim::Device sip(top::Model::sip);
  const UdpTraits t = sip.udp_traits();
  EXPECT_TRUE(t.ephemeral_reply_port);
  EXPECT_TRUE(t.fan_out);
  EXPECT_TRUE(t.duplicate);
  EXPECT_EQ(top::client_port(top::Model::sip), kClient);
  // 20260917T051804Z-queries: 8080 asks three times, 9004 three times,
  // 55777 three times: every reply reaches 9004 twice, and the last port
  // but 9004 that asked (8080 while 9004 asks; not 8080 once 55777 asks).
  const std::vector<Ports> got =
      replay(Fanout(t, kClient), {8080, 8080, 8080, 9004, 9004, 9004, 55777, 55777, 55777});
  for (std::size_t i = 0; i < got.size(); ++i)
    EXPECT_EQ(got[i], (Ports{i < 6 ? std::uint16_t{8080} : std::uint16_t{55777}, kClient, kClient}))
        << i;
}

TEST(Fanout, RoutingSessionAsModelled) {
  // 20260917T045021Z-routing: 48611, 9004, 8080, 9004, 48611, 9004. The
  // camera's fifth reply also reached 8080 (the port before the last other
  // one): the one exchange of its sessions the rule does not follow.
  const UdpTraits t{true, true, true};
  const std::vector<Ports> got = replay(Fanout(t, kClient), {48611, 9004, 8080, 9004, 48611, 9004});
  const std::vector<Ports> want = {{48611, kClient, kClient}, {48611, kClient, kClient},
                                   {8080, kClient, kClient},  {8080, kClient, kClient},
                                   {48611, kClient, kClient}, {48611, kClient, kClient}};
  EXPECT_EQ(got, want);
}

TEST(Fanout, OneCopyWithoutTheDuplicate) {
  // 20260917T044930Z-queries: one copy to 9004.
  const std::vector<Ports> got =
      replay(Fanout(UdpTraits{true, true, false}, kClient), {8080, 9004, 48182});
  EXPECT_EQ(got, (std::vector<Ports>{{8080, kClient}, {8080, kClient}, {48182, kClient}}));
}

TEST(Fanout, PushesGoWhereTheLastReplyWent) {
  Fanout f(UdpTraits{true, true, true}, kClient);
  EXPECT_TRUE(f.push().empty());  // nobody asked yet
  f.request(8080);
  EXPECT_EQ(f.push(), (Ports{8080, kClient, kClient}));
  f.request(kClient);
  EXPECT_EQ(f.push(), (Ports{8080, kClient, kClient}));
  // a request from another host starts afresh: its 9004 only
  f.request(kClient, true);
  EXPECT_EQ(f.push(), (Ports{kClient, kClient}));
}

TEST(Fanout, TheDocumentAnswersTheClientPortOnce) {
  // Topotek V1.1.3: replies go to UDP 9004, whatever port asked.
  EXPECT_EQ(replay(Fanout(UdpTraits{}, kClient), {8080, 9004, 48182}),
            (std::vector<Ports>{{kClient}, {kClient}, {kClient}}));
  // --duplicate on alone: twice there.
  EXPECT_EQ(replay(Fanout(UdpTraits{false, false, true}, kClient), {8080}),
            (std::vector<Ports>{{kClient, kClient}}));
  // No client port (SkyDroid, --reply-port 0): the asking port.
  EXPECT_EQ(replay(Fanout(UdpTraits{}, 0), {40000, 40001}), (std::vector<Ports>{{40000}, {40001}}));
  EXPECT_EQ(replay(Fanout(UdpTraits{true, true, true}, 0), {40000, 40001}),
            (std::vector<Ports>{{40000}, {40001}}));
  // Every model without the traits, and the document profile, routes so.
  for (top::Model m : top::all_models()) {
    topsim::DeviceOptions doc;
    doc.profile = top::Profile::document;
    EXPECT_EQ(topsim::Device(m, doc).udp_traits(), UdpTraits{}) << top::to_string(m);
    if (m != top::Model::sip) {
      EXPECT_EQ(topsim::Device(m).udp_traits(), UdpTraits{}) << top::to_string(m);
    }
  }
}

TEST(Fanout, EachSwitchOverridesItsTrait) {
  topsim::DeviceOptions o;
  o.ephemeral_reply_port = false;
  EXPECT_EQ(topsim::Device(top::Model::sip, o).udp_traits(), (UdpTraits{false, true, true}));
  o = {};
  o.fan_out = false;
  EXPECT_EQ(topsim::Device(top::Model::sip, o).udp_traits(), (UdpTraits{true, false, true}));
  o = {};
  o.duplicate = false;
  EXPECT_EQ(topsim::Device(top::Model::sip, o).udp_traits(), (UdpTraits{true, true, false}));
  o = {};
  o.profile = top::Profile::document;
  o.fan_out = true;
  EXPECT_EQ(topsim::Device(top::Model::sip, o).udp_traits(), (UdpTraits{false, true, false}));
}

}  // namespace
