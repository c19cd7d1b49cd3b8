// topsim's device faults (sim/device.hpp DeviceFaults, parsed by
// sim/faults.hpp): each parsed and validated with an error naming the item,
// and what each does to the device, on its own clock. The diagnoses topdump
// names on recordings of them: fault_diagnoses_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/device.hpp"
#include "sim/faults.hpp"
#include "sim_test_util.hpp"
#include "top/diagnoses.hpp"

namespace {

using topsim::Device;
using topsim::Link;

topsim::DeviceOptions with(const std::string& spec) {
  topsim::DeviceOptions o;
  o.faults = faults_of(spec).device;
  return o;
}

// The times (us) of the pushes of `ident` from 0 to `until`.
std::vector<std::uint64_t> pushes(Device& d, std::string_view ident, std::uint64_t until) {
  std::vector<std::uint64_t> at;
  for (std::uint64_t t = d.next_timer(); t <= until; t = d.next_timer()) {
    std::vector<std::string> out;
    d.poll(t, out);
    for (const std::string& s : out)
      if (top::parse_exact(s).frame.ident_view() == ident) at.push_back(t);
  }
  return at;
}

TEST(DeviceFaults, ParseAndRejectWithTheItemNamed) {
  std::string err;
  auto c = topsim::parse_faults(
      "stall=GAC@1.5+2,no-stream=GIA,ignore-motion=GAY+GSP,invert=pitch:rate,invert=yaw,"
      "placeholder-identity,refuse-tracking,clock=month-early",
      err);
  ASSERT_TRUE(c.has_value()) << err;
  const topsim::DeviceFaults& f = c->device;
  ASSERT_EQ(f.mutes.size(), 2u);
  EXPECT_EQ(f.mutes[0].ident, "GAC");
  EXPECT_EQ(f.mutes[0].from_us, 1500000u);
  EXPECT_EQ(f.mutes[0].until_us, 3500000u);
  EXPECT_EQ(f.mutes[1].ident, "GIA");
  EXPECT_EQ(f.mutes[1].from_us, 0u);
  EXPECT_EQ(f.mutes[1].until_us, topsim::DeviceFaults::kForever);
  EXPECT_EQ(f.ignore_motion, (std::vector<std::string>{"GAY", "GSP"}));
  EXPECT_EQ(f.invert[0], topsim::DeviceFaults::kInvertAngle | topsim::DeviceFaults::kInvertRate);
  EXPECT_EQ(f.invert[1], topsim::DeviceFaults::kInvertRate);
  EXPECT_EQ(f.invert[2], 0);
  EXPECT_TRUE(f.placeholder_identity && f.refuse_tracking && f.clock_month_early);
  EXPECT_TRUE(c->any());
  EXPECT_FALSE(topsim::FaultConfig{}.any());
  for (const char* bad : {"stall=GAC",
                          "stall=GAC@1",
                          "stall=GAC@1+0",
                          "stall=GAC@x+1",
                          "stall=GAC@-1+1",
                          "stall=GAC@1+4000",
                          "stall=GAY@1+1",
                          "stall",
                          "no-stream=VER",
                          "no-stream",
                          "ignore-motion=VER",
                          "ignore-motion=GAY+",
                          "ignore-motion",
                          "invert=up",
                          "invert=pitch:",
                          "invert=pitch:speed",
                          "invert",
                          "placeholder-identity=1",
                          "refuse-tracking=yes",
                          "clock=1970",
                          "clock"}) {
    EXPECT_FALSE(topsim::parse_faults(bad, err).has_value()) << bad;
    EXPECT_NE(err.find(std::string("'") + bad + "'"), std::string::npos) << bad << ": " << err;
  }
  // listed with the others (--help, topconf --sim-fault)
  for (const char* name : {"stall", "no-stream", "ignore-motion", "invert", "placeholder-identity",
                           "refuse-tracking", "clock"}) {
    const auto& n = topsim::fault_names();
    EXPECT_NE(std::find(n.begin(), n.end(), name), n.end()) << name;
    EXPECT_NE(topsim::fault_usage().find(name), std::string_view::npos) << name;
  }
}

// stall=GAC@1+1: 10 Hz pushes, none from 1 s to 2 s after GAA, then again.
TEST(DeviceFaults, StallStopsThePushAndResumes) {
  Device d(top::Model::c12, with("stall=GAC@1+1"));
  ask(d, "#TPUG2wGAA0A", 0);
  const auto at = pushes(d, "GAC", 3000000);
  std::size_t before = 0, during = 0, after = 0;
  for (std::uint64_t t : at) (t < 1000000 ? before : t < 2000000 ? during : after)++;
  EXPECT_EQ(before, 9u);  // 0.1 .. 0.9 s
  EXPECT_EQ(during, 0u);
  EXPECT_EQ(after, 11u);  // 2.0 .. 3.0 s
  // measured from the switch-on: a stream switched on later stalls later
  Device late(top::Model::c12, with("stall=GAC@1+1"));
  ask(late, "#TPUG2wGAA0A", 5000000);
  const auto at2 = pushes(late, "GAC", 8000000);
  ASSERT_FALSE(at2.empty());
  EXPECT_EQ(at2.front(), 5100000u);
  for (std::uint64_t t : at2) EXPECT_TRUE(t < 6000000 || t >= 7000000) << t;
}

// no-stream=: the switch is echoed (SkyDroid GAA, Topotek GIA: the fault's
// firmware answers it, where the healthy Topotek device is silent) and read
// back on, no push ever comes.
TEST(DeviceFaults, NoStreamAnswersTheSwitchAndNeverPushes) {
  Device sky(top::Model::c12, with("no-stream=GAC"));
  const auto echo = ask(sky, "#TPUG2wGAA0A", 0);
  ASSERT_EQ(echo.size(), 1u);
  EXPECT_EQ(echo[0].ident_view(), "GAA");
  EXPECT_TRUE(pushes(sky, "GAC", 3000000).empty());
  Device sip(top::Model::sip, with("no-stream=GIA"));
  const auto on = ask(sip, "#TPPG2wGIA01", 0);
  ASSERT_EQ(on.size(), 1u);
  EXPECT_EQ(on[0].data(), "01");
  const auto read = ask(sip, "#TPPG2rGIA00", 100000);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].data(), "01");
  EXPECT_TRUE(pushes(sip, "GIA", 3000000).empty());
  // the healthy device pushes, and reads its switch on (a bug: the GIA read
  // looked for the document's GIC stream, and answered 00 while GIA pushed)
  Device ok(top::Model::sip);
  EXPECT_TRUE(ask(ok, "#TPPG2wGIA01", 0).empty());  // top::write_reply: nothing
  EXPECT_EQ(ask(ok, "#TPPG2rGIA00", 100000).at(0).data(), "01");
  EXPECT_GE(pushes(ok, "GIA", 1000000).size(), 9u);
}

// placeholder-identity: every read that names the device answers a factory
// placeholder as top::is_placeholder_identity knows them; the healthy
// device's do not.
TEST(DeviceFaults, PlaceholderIdentityAnswersPlaceholders) {
  struct Read {
    top::Model model;
    const char* request;
  };
  for (const Read& r :
       {Read{top::Model::c12, "#TPUD2rVER00"}, Read{top::Model::c12, "#TPUD2rMOD00"},
        Read{top::Model::c13, "#TPUD2rVER00"}, Read{top::Model::sip, "#TPPD2rVSN00"},
        Read{top::Model::sip, "#TPPG2rPA200"}, Read{top::Model::sip, "#TPPG2rVER00"}}) {
    Device bad(r.model, with("placeholder-identity"));
    Device good(r.model);
    const auto b = ask(bad, r.request, 0), g = ask(good, r.request, 0);
    ASSERT_EQ(b.size(), 1u) << r.request;
    ASSERT_EQ(g.size(), 1u) << r.request;
    EXPECT_TRUE(top::is_placeholder_identity(b[0].data())) << r.request << ": " << b[0].raw;
    EXPECT_FALSE(top::is_placeholder_identity(g[0].data())) << r.request << ": " << g[0].raw;
  }
}

// clock=month-early: a date set is answered one month early (January: the
// December before); the healthy device echoes it (SkyDroid 2.3.1) or says
// nothing (Topotek: the document gives TIM and UTC writes no reply form).
TEST(DeviceFaults, ClockAnswersTheDateOneMonthEarly) {
  struct Set {
    top::Model model;
    const char* request;
    const char* answer;
  };
  for (const Set& s : {
           Set{top::Model::c12, "#tpUDFwTIM143005.00261126", "143005.00261026"},
           Set{top::Model::c12, "#tpUDFwTIM143005.00150126", "143005.00151225"},
           Set{top::Model::sip, "#tpPDEwTIM20261126143005", "20261026143005"},
           Set{top::Model::sip, "#tpPDEwTIM20260115143005", "20251215143005"},
           Set{top::Model::sip, "#tpPDCwUTC143005261126", "143005261026"},
       }) {
    Device bad(s.model, with("clock=month-early"));
    Device good(s.model);
    const auto b = ask(bad, s.request, 0), g = ask(good, s.request, 0);
    ASSERT_EQ(b.size(), 1u) << s.request;
    EXPECT_EQ(b[0].data(), s.answer) << s.request;
    if (s.model == top::Model::sip) {
      EXPECT_TRUE(g.empty()) << s.request;
      continue;
    }
    ASSERT_EQ(g.size(), 1u) << s.request;
    EXPECT_EQ(g[0].data(), std::string_view(s.request).substr(10)) << s.request;
  }
}

// refuse-tracking: TRC reads state 4 from the start and after a TRC 02.
TEST(DeviceFaults, RefuseTrackingAnswersState4) {
  Device d(top::Model::sip, with("refuse-tracking"));
  const auto r = ask(d, "#TPPD2rTRC00", 0);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].data(), "04");
  EXPECT_TRUE(top::refuses_tracking(top::Dialect::topotek, "TRC", r[0].data()));
  ask(d, "#TPPD2wTRC02", 100000);
  const auto again = ask(d, "#TPPD2rTRC00", 200000);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].data(), "04");
  Device ok(top::Model::sip);
  EXPECT_EQ(ask(ok, "#TPPD2rTRC00", 0).at(0).data(), "00");
}

// invert= and ignore-motion=: a pitch rate of +10 deg/s for 1 s (SkyDroid
// GSP 14, Topotek YPR) moves pitch +10 on the healthy device, -10 with
// invert=pitch:rate, and not at all with ignore-motion, while still echoed;
// invert=pitch:angle leaves the rate alone.
TEST(DeviceFaults, InvertAndIgnoreMotion) {
  struct Run {
    top::Model model;
    const char* rate;  // a rate command, refreshed every 50 ms for 1 s
    const char* ident;
  };
  for (const Run& r : {Run{top::Model::c12, "#TPUG2wGSP14", "GSP"},
                       Run{top::Model::sip, "#tpPG6wYPR00F400", "YPR"}}) {
    auto pitch_after = [&](const std::string& spec, std::size_t* echoes) {
      Device d(r.model, with(spec));
      for (std::uint64_t t = 0; t < 1000000; t += 50000) {
        const auto out = ask(d, r.rate, t);
        if (echoes) *echoes += out.size();
      }
      d.advance(1000000);
      return d.pitch().angle;
    };
    const double healthy = pitch_after("", nullptr);
    EXPECT_GT(std::fabs(healthy), 5.0) << r.ident;
    EXPECT_NEAR(pitch_after("invert=pitch:rate", nullptr), -healthy, 1e-6) << r.ident;
    EXPECT_NEAR(pitch_after("invert=pitch", nullptr), -healthy, 1e-6) << r.ident;
    EXPECT_NEAR(pitch_after("invert=pitch:angle", nullptr), healthy, 1e-6) << r.ident;
    EXPECT_NEAR(pitch_after("invert=yaw", nullptr), healthy, 1e-6) << r.ident;
    std::size_t echoes = 0;
    EXPECT_DOUBLE_EQ(pitch_after(std::string("ignore-motion=") + r.ident, &echoes), 0) << r.ident;
    EXPECT_EQ(echoes, 20u) << r.ident;
  }
  // angles: GAY to 10 deg, the other way with invert=yaw:angle
  auto yaw_after = [](const std::string& spec) {
    Device d(top::Model::sip, with(spec));
    ask(d, "#tpPG6wGAY03E863", 0);
    d.advance(5000000);
    return d.yaw().angle;
  };
  EXPECT_NEAR(yaw_after(""), 10, 1e-6);
  EXPECT_NEAR(yaw_after("invert=yaw:angle"), -10, 1e-6);
  EXPECT_NEAR(yaw_after("invert=yaw:rate"), 10, 1e-6);
  EXPECT_DOUBLE_EQ(yaw_after("ignore-motion=GAY"), 0);
}

}  // namespace
