// topconf run --driver (issue 49): the default topsim is compatible with
// the drivers that fly it; and on topsim variants the verdict topconf gives
// agrees with what the driver-like client (topotek_client.hpp, which reads
// the same profile) lives through over a real pseudo-terminal. A client
// served against a device topconf calls incompatible, or the reverse, is a
// bug in the profile.
#include "drivers/compat.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "compat_util.hpp"
#include "driver_harness.hpp"
#include "sim/faults.hpp"
#include "topotek_client.hpp"

namespace {

TEST(DriverVerdict, TheDefaultTopsimIsCompatible) {
  for (const auto& [driver, model] : {std::pair{"ardupilot-topotek", "sip"},
                                      {"ardupilot-skydroid", "c12"},
                                      {"ardupilot-skydroid", "c13"}}) {
    SCOPED_TRACE(std::string(driver) + " " + model);
    const Verdict v = topconf_driver(driver, model, "", std::string(driver) + "_" + model);
    EXPECT_EQ(v.rc, 0);
    ASSERT_TRUE(v.compat.is_object());
    EXPECT_EQ(v.verdict(), "compatible");
    EXPECT_EQ(v.compat.value("text", ""), "compatible");
    EXPECT_EQ(v.compat.value("driver", ""), driver);
    EXPECT_FALSE(v.compat["needs"].empty());
    for (const auto& n : v.compat["needs"]) EXPECT_FALSE(n.value("protects", "").empty());
  }
}

TEST(DriverVerdict, ABreakingFaultIsIncompatibleWithExitOne) {
  const Verdict v = topconf_driver("ardupilot-skydroid", "c13", "--sim-fault no-stream=GAC",
                                   "skydroid_no_stream");
  EXPECT_EQ(v.rc, 1);
  EXPECT_EQ(v.verdict(), "incompatible");
  EXPECT_NE(v.compat.value("text", "").find("attitude"), std::string::npos);
}

TEST(DriverVerdict, AnUnknownDriverOrModelIsBadUsage) {
  EXPECT_EQ(run_cmd(bin("topconf") + " run --driver no-such-driver"), 2);
  EXPECT_EQ(run_cmd(bin("topconf") + " run --driver ardupilot-topotek --model c12"), 2);
  EXPECT_EQ(run_cmd(bin("topconf") + " drivers"), 0);
}

// The harness stamps a frame when it reads it, so the last attitude can
// come just after the run's end: healthy, not 2^64 us before the end (a
// flaky agreement failure until the rule said so).
TEST(DriverVerdict, AnAttitudeReadJustAfterTheEndIsFresh) {
  struct A {
    std::uint64_t t_us;
  };
  const std::uint64_t start = 1000000, ms = 3000, end = start + ms * 1000;
  std::vector<A> att;
  for (std::uint64_t t = start + 100000; t <= end + 2000; t += 100000) att.push_back({t});
  att.push_back({end + 2000});
  EXPECT_TRUE(healthy_throughout(att, start, ms));
  EXPECT_NE(attitude_times(att, start, ms).find(", last 0 ms before the end"), std::string::npos);
  att.resize(att.size() - 20);  // the last 2 s without attitude: stale at the end
  EXPECT_FALSE(healthy_throughout(att, start, ms));
}

// The verdict's text: its level's name, then the features lost or the
// reasons (one home of the names: drivers::to_string).
TEST(DriverVerdict, TheTextNamesTheLevelThenWhatItLists) {
  using Level = drivers::Compatibility::Level;
  drivers::Compatibility c;
  c.features = {"zoom", "video"};
  c.reasons = {"attitude: lost", "yaw: stuck"};
  const std::pair<Level, const char*> want[] = {
      {Level::compatible, "compatible"},
      {Level::without, "compatible without: zoom, video"},
      {Level::incompatible, "incompatible: attitude: lost; yaw: stuck"},
      {Level::unreachable, "unreachable: attitude: lost; yaw: stuck"}};
  for (const auto& [level, text] : want) {
    c.level = level;
    EXPECT_EQ(c.text(), text);
  }
  EXPECT_EQ(drivers::to_string(drivers::Grade::should), "should");
  EXPECT_EQ(drivers::to_string(drivers::LinkKind::serial), "serial");
}

// A driver case's matrix level is its need's grade (info is the matrix's
// may), and its section the need's source as topconf drivers names it.
TEST(DriverMatrix, LevelFromTheGradeAndSectionFromTheSource) {
  EXPECT_EQ(drivers::to_string(drivers::Source{"o/r", "a/b.cpp", "PR #1"}), "o/r a/b.cpp @ PR #1");
  std::set<std::string> levels;
  for (const drivers::Profile& p : drivers::profiles()) {
    SCOPED_TRACE(std::string(p.name));
    const auto m = drivers::driver_matrix_json(p, p.models.front());
    for (const drivers::Need& n : p.needs) {
      const std::string id = drivers::case_id(p, n);
      const auto k = std::find_if(m["cases"].begin(), m["cases"].end(),
                                  [&](const auto& c) { return c["id"] == id; });
      ASSERT_NE(k, m["cases"].end()) << id;
      const std::string level = (*k)["level"];
      levels.insert(level);
      EXPECT_EQ(level, n.grade == drivers::Grade::info ? "may" : drivers::to_string(n.grade)) << id;
      EXPECT_EQ((*k)["section"],
                drivers::to_string(p.sources.at(static_cast<std::size_t>(n.source))))
          << id;
    }
  }
  EXPECT_EQ(levels, (std::set<std::string>{"must", "should", "may"}));
}

// What the ArduPilot Topotek client lived through: healthy on 12-char GIA
// frames (healthy_throughout), and the features it lost.
Experience topotek_experience(const std::string& faults, topsim::DeviceOptions o) {
  std::string err;
  const auto fc = topsim::parse_faults(faults, err);
  EXPECT_TRUE(fc) << err;
  TopotekClient c;
  const std::uint64_t ms = 3000;
  const DriverRun r = run_driver(c, top::Model::sip, topsim::TransportKind::pty, ms, "", o,
                                 fc ? *fc : topsim::FaultConfig{});
  Experience e;
  e.served = healthy_throughout(c.attitude, r.start_us, ms);
  e.why = attitude_times(c.attitude, r.start_us, ms);
  if (!c.version_parsed || (c.version[0] | c.version[1] | c.version[2]) == 0)
    e.lost.insert("firmware version");
  if (c.model_name.empty() || c.model_name.find_first_not_of('0') == std::string::npos)
    e.lost.insert("model name");
  if (!c.sd_ok) e.lost.insert("photo and video");
  if (c.track_states.empty() ||
      std::find(c.track_states.begin(), c.track_states.end(), '4') != c.track_states.end())
    e.lost.insert("tracking");
  return e;
}

class TopotekVariant : public ::testing::TestWithParam<const char*> {};

// topconf's in-process topsim and the client's topsim over a pty, with the
// same fault.
TEST_P(TopotekVariant, TheVerdictIsWhatTheClientLivesThrough) {
  const std::string faults = GetParam();
  const std::string stem = variant_stem("topotek_" + faults);
  const Verdict v = topconf_driver("ardupilot-topotek", "sip",
                                   faults.empty() ? "" : "--sim-fault '" + faults + "'", stem);
  expect_agreement(v, topotek_experience(faults, {}), faults.empty() ? "default" : faults);
}

INSTANTIATE_TEST_SUITE_P(Faults, TopotekVariant,
                         ::testing::Values("", "placeholder-identity", "no-stream=GIA",
                                           "refuse-tracking", "ignore=VSN", "ignore=SDC",
                                           "ignore=PA2", "ignore=GIA", "stall=GIA@0.5+1.5"));

class TopotekVariantOptions : public ::testing::TestWithParam<OptionsVariant> {};

// Variants of the device's own options, not faults, over a real
// pseudo-terminal both ways: topconf against a topsim process, the client
// against the harness's topsim with the same options.
TEST_P(TopotekVariantOptions, TheVerdictIsWhatTheClientLivesThrough) {
  const OptionsVariant& p = GetParam();
  const Verdict v = options_verdict("ardupilot-topotek", p, true);
  expect_pinned(v, p);
  expect_agreement(v, topotek_experience("", options_of(p)), p.name);
}

// The document profile: GIC pushes, no GIA, the attitude the driver cannot
// read. Request-order replies and pushes are served. The version as 123,
// without its dots (ArduPilot PR #27568's firmware): the driver since that
// PR reads it digit by digit. A device that echoes every write, the
// enable's 2-char GIA echo among them: the driver (as the client models
// it) takes its attitude from the 12-char frames only; issue 50's
// echo-as-attitude bug is the driver that does not.
INSTANTIATE_TEST_SUITE_P(
    Options, TopotekVariantOptions,
    ::testing::Values(OptionsVariant{"GicOnlyAttitudeIsIncompatibleForBoth", "sip",
                                     setting::document_profile(), "incompatible"},
                      OptionsVariant{"RequestOrderRepliesAndPushesAreServed", "sip",
                                     setting::request_order_replies_and_pushes(), "compatible"},
                      OptionsVariant{"AVersionWithoutDots", "sip", setting::fw_version("123"),
                                     "compatible"},
                      OptionsVariant{"EchoedWrites", "sip", setting::write_echo(), "compatible"}),
    variant_name);

}  // namespace
