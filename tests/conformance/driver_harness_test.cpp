// The harness itself: a client that asks one thing 10 times a second gets
// its answers over a real pty and UDP, and topdump reads topsim's recording
// of the run without a warning.
#include "driver_harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "top/frame.hpp"

namespace {

// Asks the SkyDroid version (SkyDroid 4.1, VER) every 100 ms.
class AskVersion : public DriverClient {
 public:
  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    out.push_back(top::build_frame({.header = top::Header::fixed,
                                    .src = client,
                                    .dst = 'D',
                                    .control = 'r',
                                    .ident = "VER",
                                    .data = "00"}));
    ++asked;
    return now_us + 100000;
  }
  void on_frame(const top::Frame& f, std::uint64_t) override {
    if (f.ident_view() == "VER" && f.dst == client) ++answered;
  }
  int asked = 0, answered = 0;
};

class Harness : public ::testing::TestWithParam<topsim::TransportKind> {};

TEST_P(Harness, AnswersArriveAndTheRecordingReadsClean) {
  const DriverLink l{GetParam()};
  const std::string rec = recording_path(std::string("driver_harness_") + l.name(), l.kind);
  AskVersion c;
  // TCP only where the port rules give a model TCP: the C10 (SkyDroid
  // 2.1.1: also on TCP 5000; the C20, TCP only, takes no VER); the C12 has
  // a pty and UDP.
  const top::Model model = l.kind == topsim::TransportKind::tcp ? top::Model::c10 : top::Model::c12;
  const DriverRun r = run_driver(c, model, l.kind, 1000, rec);
  EXPECT_GE(c.asked, 9);
  EXPECT_GE(c.answered, c.asked - 1) << "sent " << r.sent << ", received " << r.received;
  const Dump d = topdump_findings(rec);
  EXPECT_EQ(d.status, 0) << describe(d);
  EXPECT_TRUE(d.findings.empty()) << describe(d);
  EXPECT_GT(d.lines, 18u);
  std::remove(rec.c_str());
}

INSTANTIATE_TEST_SUITE_P(Links, Harness,
                         ::testing::Values(topsim::TransportKind::pty, topsim::TransportKind::udp,
                                           topsim::TransportKind::tcp),
                         [](const auto& i) { return std::string(DriverLink{i.param}.name()); });

// The links follow the port rules (top::known_ports): TCP for the models a
// document gives a TCP port (SkyDroid 2.1.1: the C10 also on TCP 5000, the
// C20 on TCP 5000 only), and for none of the drivers' models (issue 28).
TEST(DriverLinks, FollowThePortRules) {
  using K = topsim::TransportKind;
  using Links = std::vector<K>;
  EXPECT_EQ(driver_links(top::Model::sip), (Links{K::pty, K::udp}));
  EXPECT_EQ(driver_links(top::Model::c12), (Links{K::pty, K::udp}));
  EXPECT_EQ(driver_links(top::Model::c13), (Links{K::pty, K::udp}));
  EXPECT_EQ(driver_links(top::Model::c10), (Links{K::pty, K::udp, K::tcp}));
  const Links c20 = driver_links(top::Model::c20);
  EXPECT_NE(std::find(c20.begin(), c20.end(), K::tcp), c20.end());
}

}  // namespace
