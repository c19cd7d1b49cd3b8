// ArduPilot's Topotek driver, as a client written from its facts
// (topotek_client.hpp), against topsim --model sip over a real pty and UDP:
// the driver is healthy, its pitch target is reached, identity, SD card,
// recording and tracking work, nothing is refused, and topdump reads
// topsim's recording of the run without a warning.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "driver_harness.hpp"
#include "topotek_client.hpp"

namespace {

// The vehicle's requests over the run, by time since the first tick.
class Scripted : public TopotekClient {
 public:
  static constexpr std::uint64_t kPitchAt = 1500000, kRateAt = 2500000, kStopAt = 3000000,
                                 kAngleAt = 3500000, kRecOnAt = 4000000, kRecOffAt = 4500000,
                                 kTrackAt = 5000000, kCancelAt = 7000000;
  std::uint64_t start = 0;
  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    if (start == 0) start = now_us;
    const std::uint64_t t = now_us - start;
    auto once = [&](std::uint64_t at, bool& done) { return t >= at && !done && (done = true); };
    if (once(kPitchAt, pitch_done)) pitch = -30, pitch_cmd_us = now_us;
    if (once(kRateAt, rate_done)) rate_mode = true, yaw_rate = 10;
    if (once(kStopAt, stop_done)) yaw_rate = 0;
    if (once(kAngleAt, angle_done)) rate_mode = false;
    if (once(kRecOnAt, rec_on_done)) record(true);
    if (once(kRecOffAt, rec_off_done)) record(false);
    if (once(kTrackAt, track_done)) track_centre(), oft_before_track = oft;
    if (once(kCancelAt, cancel_done)) cancel_tracking(), states_before_cancel = track_states.size();
    return TopotekClient::tick(now_us, out);
  }
  std::uint64_t pitch_cmd_us = 0;
  int oft_before_track = 0;
  std::size_t states_before_cancel = 0;

 private:
  bool pitch_done = false, rate_done = false, stop_done = false, angle_done = false,
       rec_on_done = false, rec_off_done = false, track_done = false, cancel_done = false;
};

class TopotekDriver : public ::testing::TestWithParam<topsim::TransportKind> {};

TEST_P(TopotekDriver, IsServedAndTheRecordingReadsClean) {
  const DriverLink l{GetParam()};
  const std::string rec = recording_path(std::string("driver_topotek_") + l.name(), l.kind);
  Scripted c;
  const DriverRun r = run_driver(c, top::Model::sip, l.kind, 8500, rec);
  SCOPED_TRACE(std::string(l.name()) + ": sent " + std::to_string(r.sent) + ", received " +
               std::to_string(r.received));

  // Healthy: attitude from full 12-char GIA frames at 5 Hz or more, never
  // more than the driver's 1 s health timeout apart.
  ASSERT_GE(c.attitude.size(), 2u);
  const double span_s = static_cast<double>(c.attitude.back().t_us - c.attitude.front().t_us) / 1e6;
  EXPECT_GE(static_cast<double>(c.attitude.size() - 1) / span_s, 5.0);
  for (std::size_t i = 1; i < c.attitude.size(); ++i)
    EXPECT_LT(c.attitude[i].t_us - c.attitude[i - 1].t_us, 1000000u) << i;
  EXPECT_LT(c.attitude.front().t_us - r.start_us, 1500000u);

  // Pitch within 5 deg of the -30 target within 1 s of the command, and
  // level before it.
  ASSERT_NE(c.pitch_cmd_us, 0u);
  std::uint64_t reached = 0;
  for (const auto& a : c.attitude) {
    if (a.t_us < c.pitch_cmd_us) {
      EXPECT_NEAR(a.pitch, 0, 0.5);
    }
    if (a.t_us >= c.pitch_cmd_us && std::fabs(a.pitch + 30) <= 5 && !reached) reached = a.t_us;
  }
  ASSERT_NE(reached, 0u);
  EXPECT_LE(reached - c.pitch_cmd_us, 1000000u);
  // The yaw rate turned the gimbal right, and the angle targets took it back.
  const auto yaw_max = std::max_element(c.attitude.begin(), c.attitude.end(),
                                        [](auto& a, auto& b) { return a.yaw < b.yaw; });
  EXPECT_GT(yaw_max->yaw, 2.0);
  EXPECT_NEAR(c.attitude.back().yaw, 0, 0.5);
  EXPECT_NEAR(c.attitude.back().pitch, -30, 0.5);

  // Identity: the real unit's version 1.6.26.R.D reads as v1.6.26.
  EXPECT_TRUE(c.version_parsed);
  EXPECT_EQ(c.version[0], 1);
  EXPECT_EQ(c.version[1], 6);
  EXPECT_EQ(c.version[2], 26);
  EXPECT_EQ(c.model_name, "SIP");
  // SD card state parsed (a card: the time is set once a second, at most 7 times).
  EXPECT_TRUE(c.sd_parsed);
  EXPECT_TRUE(c.sd_ok);
  EXPECT_GE(c.utc_sent, 5);
  // Recording toggled on, then off.
  ASSERT_GE(c.recording.size(), 2u);
  const auto on = std::find(c.recording.begin(), c.recording.end(), true);
  ASSERT_NE(on, c.recording.end());
  EXPECT_NE(std::find(on, c.recording.end(), false), c.recording.end());
  EXPECT_FALSE(c.recording.back());

  // Tracking: TRC answered; TRC 02 + LOC reaches state 2, OFT pushes arrive,
  // the cancel goes back to waiting.
  ASSERT_GE(c.track_states.size(), 6u);
  EXPECT_EQ(c.track_states.front(), '0');
  ASSERT_LE(c.states_before_cancel, c.track_states.size());
  const std::vector<char> before(
      c.track_states.begin(), c.track_states.begin() + static_cast<long>(c.states_before_cancel));
  EXPECT_NE(std::find(before.begin(), before.end(), '2'), before.end());
  EXPECT_EQ(c.track_states.back(), '1');
  EXPECT_GE(c.oft - c.oft_before_track, 30);
  EXPECT_EQ(c.oft_before_track, 0);
  EXPECT_EQ(c.ere, 0);

  // topdump on topsim's recording: no warning.
  const Dump d = topdump_findings(rec, "warning", topdump_args(top::Model::sip, l.kind));
  EXPECT_EQ(d.status, 0) << describe(d);
  EXPECT_TRUE(d.findings.empty()) << describe(d);
  std::remove(rec.c_str());
}

// The rangefinder: the driver's LRF 03 is answered with topsim's range in
// Topotek 5.9's X1X2X3X4X5.X6, which a client reading like ArduPilot's
// driver (chars 0-4 and 6) gets as the range topsim meant, and topdump
// decodes as metres without a finding. topsim's LRF answer was 5 chars
// (#tpMU5wLRF500002E, the midpoint of the document's range), which the
// driver read as 50001.4 m (the checksum's E as the tenths).
TEST_P(TopotekDriver, ReadsTheRangeTopsimMeasures) {
  const DriverLink l{GetParam()};
  const std::string rec = recording_path(std::string("driver_topotek_lrf_") + l.name(), l.kind);
  topsim::DeviceOptions o;
  o.range_m = 2345.6;
  struct OnAtStart : TopotekClient {
    bool asked = false;
    std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
      if (!asked) rangefinder(true), asked = true;
      return TopotekClient::tick(now_us, out);
    }
  } c;
  run_driver(c, top::Model::sip, l.kind, 1500, rec, o);
  ASSERT_EQ(c.lrf, 1);
  EXPECT_NEAR(c.distance_m, 2345.6, 1e-9);
  // topdump: the answer decodes as the document's result, in metres.
  int lrf = 0;
  const std::string args = topdump_args(top::Model::sip, l.kind);
  for (const auto& [line, j] : topdump_read_json(rec, args).lines) {
    // the device's frame, not its copies to the client's other ports (UDP)
    if (j.is_discarded() || j.value("type", "") != "frame" || j.value("ident", "") != "LRF" ||
        j.value("src", "") == std::string(1, c.client) ||
        !j.value("copy_of", nlohmann::json()).is_null())
      continue;
    ++lrf;
    EXPECT_EQ(j.value("data", ""), "02345.6") << line;
    const auto& d = j["fields"]["distance"];
    EXPECT_NEAR(d.value("value", 0.0), 2345.6, 1e-9) << line;
    EXPECT_EQ(d.value("unit", ""), "m") << line;
    EXPECT_TRUE(j["findings"].empty()) << line;
  }
  EXPECT_EQ(lrf, 1);
  const Dump dump = topdump_findings(rec, "warning", args);
  EXPECT_EQ(dump.status, 0) << describe(dump);
  EXPECT_TRUE(dump.findings.empty()) << describe(dump);
  std::remove(rec.c_str());
}

// Every link the port rules give the SIP: a pty and UDP (no TCP: see
// driver_links).
INSTANTIATE_TEST_SUITE_P(Links, TopotekDriver, ::testing::ValuesIn(driver_links(top::Model::sip)),
                         [](const auto& i) { return std::string(DriverLink{i.param}.name()); });

}  // namespace
