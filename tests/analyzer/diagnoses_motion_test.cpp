// The diagnoses that need more than one frame to tell (issue 29), on their
// own: the motion track fed frame by frame as the session feeds it, and a
// serial log through the session. Each test is a case an outside capture
// found (direction-inverted, refresh-gap, silent-device).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "diagnoses/direction_inverted.hpp"
#include "diagnoses/motion_track.hpp"
#include "findings/afindings.hpp"
#include "report/analysis.hpp"
#include "test_support.hpp"
#include "test_time.hpp"
#include "top/catalog.hpp"
#include "top/device.hpp"
#include "top/diagnoses.hpp"
#include "top/motion.hpp"

namespace topdump {
namespace {

// The motion track fed frame by frame, as the session feeds it. Each frame's
// data is a view into the whole frame, as the session's are (the track
// reads the eight bytes before a short datum, which every header holds).
class MotionFeed {
 public:
  explicit MotionFeed(top::Dialect d) : d_(d) {}
  void command(std::int64_t ms, std::string_view id, const std::string& data) {
    frame(ms, id, data, 'w', true);
  }
  void attitude(std::int64_t ms, std::string_view id, const std::string& data) {
    frame(ms, id, data, 'r', false);
  }
  void echo(std::int64_t ms, std::string_view id, const std::string& data) {
    frame(ms, id, data, 'w', false);
  }
  diag::MotionTrack track;
  std::vector<diag::Found> finish(std::int64_t ms) {
    track.finish(kT0 + ms * 1000);
    std::vector<diag::Found> v;
    track.verdicts([&](diag::Found f) { v.push_back(std::move(f)); });
    return v;
  }

 private:
  void frame(std::int64_t ms, std::string_view id, const std::string& data, char control,
             bool request) {
    const top::MotionSpec* m = top::motion_of(d_, id);
    const top::CommandSpec* c = top::find_command(d_, id);
    ASSERT_TRUE(m && c) << id;
    const top::FormSpec* form = nullptr;
    for (const top::FormSpec& f : c->forms)
      if (f.control == control && f.min_length <= data.size() && data.size() <= f.max_length)
        form = &f;
    ASSERT_TRUE(form) << id << " " << data;
    frames_.push_back("#tpUG6" + std::string(1, control) + std::string(id) + data + "00");
    const std::string_view whole = frames_.back();
    track.frame(*m, form, request, control, whole.substr(10, data.size()), ++n_, kT0 + ms * 1000,
                request ? 0 : 1, top::Model::unknown);
  }
  top::Dialect d_;
  std::uint64_t n_ = 0;
  std::deque<std::string> frames_;
};

std::string hex4(double deg) {  // hex_s, 0.01 deg, 16 bits
  char b[8];
  std::snprintf(b, sizeof b, "%04X", static_cast<unsigned>(std::lround(deg * 100)) & 0xFFFFu);
  return b;
}

bool has(const std::vector<diag::Found>& v, top::Diagnosis d) {
  return std::any_of(v.begin(), v.end(), [&](const diag::Found& f) { return f.code == d; });
}

// A yaw pan of more than 180 deg (Topotek YPR yaw 30 counts, about 24.6
// deg/s, for 8 s) is measured across the turn: the short way round it read
// as a turn the other way and named direction-inverted (found by an outside
// capture). Its mirror, a pan that does turn the other way, still is.
TEST(DiagnosesMotion, YawPanPast180IsMeasuredWhole) {
  for (const int turns : {1, -1}) {
    MotionFeed f(top::Dialect::topotek);
    for (std::int64_t ms = 0; ms <= 11000; ms += 50) {
      const double moved =
          24.576 * static_cast<double>(std::clamp<std::int64_t>(ms - 1000, 0, 8000)) / 1000;
      f.attitude(ms, "GIA", hex4(std::remainder(turns * moved, 360.0)) + "0000" + "0000");
      if (ms >= 1000 && ms < 9000 && ms % 100 == 0) f.command(ms, "YPR", "1E0000");
      if (ms >= 9000 && ms < 9300 && ms % 100 == 0) f.command(ms, "YPR", "000000");
    }
    const auto v = f.finish(11000);
    EXPECT_EQ(has(v, top::Diagnosis::direction_inverted), turns < 0) << turns;
    EXPECT_FALSE(has(v, top::Diagnosis::axis_left_moving)) << turns;
  }
}

// The case reads the command as the wire carries it, then what it means:
// a Topotek GIP of +30.00 is 30 deg down (ArduPilot PR #29002), and an
// outside capture read "GIP to -30.0 deg" beside a frame decoded as
// "angle 30.00 deg". Rates name their speed in deg/s, not only the count.
TEST(DiagnosesMotion, TheCaseShowsTheWireValueAndItsMeaning) {
  MotionFeed f(top::Dialect::topotek);
  for (std::int64_t ms = 0; ms <= 6000; ms += 100) {
    const double pitch = std::clamp<double>(static_cast<double>(ms - 1000) / 100, 0, 30);
    f.attitude(ms, "GIA", "0000" + hex4(-pitch) + "0000");  // up (GIA: down positive)
    if (ms >= 1000 && ms < 5000 && ms % 200 == 0) f.command(ms, "GIP", hex4(30) + "63");
  }
  const auto v = f.finish(6000);
  ASSERT_TRUE(has(v, top::Diagnosis::direction_inverted));
  EXPECT_NE(v[0].figure.find("GIP +30.0 deg (pitch down positive on the wire: a target of "
                             "-30.0 deg): pitch went from +0.0 to +30.0 deg (up), away from it"),
            std::string::npos)
      << v[0].figure;

  MotionFeed r(top::Dialect::topotek);
  for (std::int64_t ms = 0; ms <= 6000; ms += 100) {
    const double pitch = std::clamp<double>(static_cast<double>(ms - 1000) / 100, 0, 30);
    r.attitude(ms, "GIA", "0000" + hex4(-pitch) + "0000");
    if (ms >= 1000 && ms < 4000) r.command(ms, "YPR", "000C00");  // 12 counts down
    if (ms >= 4000 && ms < 4300) r.command(ms, "YPR", "000000");
  }
  const auto w = r.finish(6000);
  ASSERT_TRUE(has(w, top::Diagnosis::direction_inverted));
  EXPECT_NE(w[0].figure.find("YPR 12 (9.8 deg/s down): pitch moved +"), std::string::npos)
      << w[0].figure;
}

// Angle commands that return to 0 (a nod: -30, 0, -30, 0) move the gimbal
// the same way under either sign convention: they vote neither way, so the
// inverted -30s are named (counted as right, the returns outvoted them).
TEST(DiagnosesMotion, ReturnsToZeroDoNotOutvoteAnInversion) {
  diag::DirectionWatch w;
  diag::Judged j;
  j.spec = top::motion_of(top::Dialect::skydroid, "GAP");
  j.axis = static_cast<int>(top::Axis::pitch);
  j.seconds = 8;
  for (int i = 0; i < 2; ++i) {
    j.first_n = 10 + 2 * static_cast<std::uint64_t>(i);
    j.from = 0, j.target = -30, j.to = 30;  // inverted
    w.window(j);
    j.first_n += 1;
    j.from = 30, j.target = 0, j.to = 0;  // back: either convention
    w.window(j);
  }
  std::vector<diag::Found> v;
  w.verdicts([&](diag::Found f) { v.push_back(std::move(f)); });
  ASSERT_TRUE(has(v, top::Diagnosis::direction_inverted));
  EXPECT_NE(v[0].figure.find("2 of 2 pitch angle windows"), std::string::npos) << v[0].figure;
}

// A Topotek yaw range of +-150 keeps the gimbal off +-180: from +140 to
// -140 it turns through 0, 280 deg left, the way GAY asks. Taken the short
// way round, every window read as "away from it" (an outside capture of
// ArduPilot's angle mode alternating +140 and -140 on a SIP).
TEST(DiagnosesMotion, YawRangeShortOf180TurnsThroughZero) {
  MotionFeed f(top::Dialect::topotek);
  double yaw = 0;
  double target = 140;
  for (std::int64_t ms = 0; ms <= 33000; ms += 50) {
    if (ms >= 1000 && (ms - 1000) % 8000 == 0) {
      target = (ms - 1000) % 16000 == 0 ? 140 : -140;
      f.command(ms, "GAY", hex4(target) + "63");
    }
    yaw += std::clamp(target - yaw, -2.5, 2.5);  // 50 deg/s, through 0
    f.attitude(ms, "GIA", hex4(yaw) + "0000" + "0000");
  }
  const auto v = f.finish(33000);
  EXPECT_FALSE(has(v, top::Diagnosis::direction_inverted)) << (v.empty() ? "" : v[0].figure);
}

// A rate window ends where the camera's tracker takes the gimbal (Topotek
// TRC state 2, after ArduPilot's TRC 02 and LOC): the tracker's motion
// afterwards answers no command. Judged on it, a pitch pan down "moved up"
// (an outside capture of a pan, then 28 s tracking).
TEST(DiagnosesMotion, TrackingEndsTheWindowsBeforeIt) {
  for (const bool handed : {true, false}) {
    MotionFeed f(top::Dialect::topotek);
    double pitch = 0;  // GIA pitch, down positive on the wire
    for (std::int64_t ms = 0; ms <= 36000; ms += 50) {
      if (ms >= 1000 && ms < 3000 && ms % 100 == 0) f.command(ms, "YPR", "000400");
      if (ms == 3000 && handed) f.track.handover();
      pitch += ms < 3000 ? (ms >= 1000 ? 0.16 : 0) : -0.1;  // down 3.2 deg/s, then the tracker: up
      f.attitude(ms, "GIA", "0000" + hex4(pitch) + "0000");
    }
    const auto v = f.finish(36000);
    EXPECT_EQ(has(v, top::Diagnosis::direction_inverted), !handed) << handed;
  }
}

// The report's measured rate of a yaw pan across +-180 (a 10 deg/s pan
// from +170 measured 7.3 deg/s, and the speed unit "neither").
TEST(ReportRate, YawSlopeAcrossTheWrap) {
  std::vector<std::int64_t> t;
  std::vector<float> v;
  for (int i = 0; i <= 40; ++i) {
    t.push_back(kT0 + i * 100'000);
    v.push_back(static_cast<float>(std::remainder(170.0 + i * 1.0, 360.0)));  // 10 deg/s
  }
  report::Series s{&t, &v, "GAC", false};
  double rate = 0;
  std::size_t n = 0;
  ASSERT_TRUE(report::slope(s, t.front(), t.back(), true, rate, n));
  EXPECT_EQ(n, 41u);
  EXPECT_NEAR(rate, 10.0, 0.01);
}

// While the camera's tracker drives the gimbal, no command is judged: a yaw
// target sent then sits still because the tracker holds the gimbal, not
// because the firmware ignores it (ArduPilot's Topotek driver sends no target
// while its camera tracks). A topsim recording whose client sent GAY and GIP
// during tracking was command-ignored whenever two TRC polls were more than
// a window apart. Once the tracker lets go (TRC state 0), a still gimbal is
// command-ignored again.
TEST(DiagnosesMotion, NoCommandIsJudgedWhileTheTrackerDrives) {
  for (const bool released : {false, true}) {
    MotionFeed f(top::Dialect::topotek);
    double yaw = 0;
    for (std::int64_t ms = 0; ms <= 16000; ms += 50) {
      if (ms >= 500 && ms < 2500 && ms % 100 == 0) {  // YPR moves the gimbal right
        f.command(ms, "YPR", "140000");
        f.echo(ms, "YPR", "140000");
      }
      if (ms == 2500) f.command(ms, "YPR", "000000");
      if (ms == 3000) f.track.handover();  // TRC state 2
      if (released && ms == 9000) f.track.released();
      if (ms >= 3500 && ms % 100 == 0) {  // GAY to 30 deg (then -30), never followed
        const std::string target = (ms < 9000 ? hex4(30) : hex4(-30)) + "63";
        f.command(ms, "GAY", target);
        f.echo(ms, "GAY", target);
      }
      if (ms >= 500 && ms < 2500) yaw += 0.8;  // 16 deg/s
      f.attitude(ms, "GIA", hex4(yaw) + "0000" + "0000");
    }
    const auto v = f.finish(16000);
    EXPECT_EQ(has(v, top::Diagnosis::command_ignored), released) << released;
    EXPECT_FALSE(has(v, top::Diagnosis::direction_inverted)) << released;
  }
}

TEST(DiagnosesMotion, TrackingIsTrcStateTwo) {
  EXPECT_TRUE(top::reports_tracking(top::Dialect::topotek, "TRC", 'r', "02"));
  EXPECT_FALSE(top::reports_tracking(top::Dialect::topotek, "TRC", 'r', "01"));  // waiting
  // the echo of the write TRC 02 (prepare) is no state (a sip fault test
  // lost its command-ignored to it)
  EXPECT_FALSE(top::reports_tracking(top::Dialect::topotek, "TRC", 'w', "02"));
  EXPECT_FALSE(top::reports_tracking(top::Dialect::topotek, "LOC", 'r', "02"));
  EXPECT_FALSE(top::reports_tracking(top::Dialect::skydroid, "TRC", 'r', "02"));
  // and lets go on state 0, 1 or 4, or the echo of TRC 00 or 01; not on
  // state 3 (temporarily lost) nor the echo of TRC 02 (prepare)
  for (const char* d : {"00", "01", "04"})
    EXPECT_TRUE(top::releases_tracking(top::Dialect::topotek, "TRC", 'r', d)) << d;
  for (const char* d : {"00", "01"})
    EXPECT_TRUE(top::releases_tracking(top::Dialect::topotek, "TRC", 'w', d)) << d;
  EXPECT_FALSE(top::releases_tracking(top::Dialect::topotek, "TRC", 'r', "03"));
  EXPECT_FALSE(top::releases_tracking(top::Dialect::topotek, "TRC", 'r', "02"));
  EXPECT_FALSE(top::releases_tracking(top::Dialect::topotek, "TRC", 'w', "02"));
  EXPECT_FALSE(top::releases_tracking(top::Dialect::skydroid, "TRC", 'r', "00"));
}

// The speed-refresh limit is the model's: a device that names itself C13 in
// its MOD reply (no speed-refresh trait) holds a rate without refreshes,
// where a C12 or an unnamed SkyDroid stops after 1000 ms (an outside C13
// capture was told "not refreshed ... the motors stop").

TEST(DiagnosesMotion, ModelNamedByTheDeviceChoosesTheRefreshLimit) {
  EXPECT_EQ(top::model_named_by(top::Dialect::skydroid, "MOD", "C13"), top::Model::c13);
  EXPECT_EQ(top::model_named_by(top::Dialect::skydroid, "MOD", "c12 "), top::Model::c12);
  EXPECT_EQ(top::model_named_by(top::Dialect::skydroid, "MOD", "C11"), top::Model::unknown);
  EXPECT_EQ(top::model_named_by(top::Dialect::skydroid, "MOD", "SIP"), top::Model::unknown);
  EXPECT_EQ(top::model_named_by(top::Dialect::topotek, "MOD", "C13"), top::Model::unknown);
  for (const top::Model named : {top::Model::unknown, top::Model::c12, top::Model::c13}) {
    MotionFeed f(top::Dialect::skydroid);
    if (named != top::Model::unknown) f.track.named(named);
    f.command(1000, "GSP", "06");
    f.command(4000, "GSP", "00");
    const auto v = f.finish(5000);
    EXPECT_EQ(has(v, top::Diagnosis::refresh_gap), named != top::Model::c13)
        << top::to_string(named);
  }
}

// An axis still moving at the end is left moving, and its gap to the end
// no refresh-gap: the motors did not stop (an outside capture of a C12,
// refresh limit 1 s, named both of one axis). Where the attitude stops
// after the limit, the gap is named and the axis is not.
TEST(DiagnosesMotion, AnAxisMovingToTheEndIsNoRefreshGap) {
  for (const bool stops : {false, true}) {
    MotionFeed f(top::Dialect::skydroid);
    f.track.named(top::Model::c12);
    for (std::int64_t ms = 0; ms <= 8000; ms += 100) {
      const double moving = static_cast<double>(std::clamp<std::int64_t>(ms - 1000, 0, 7000));
      const double yaw = (stops ? std::min(moving, 1000.0) : moving) * 10 / 1000;
      f.attitude(ms, "GAC", hex4(yaw) + "0000" + "0000");
      if (ms >= 1000 && ms <= 2000) f.command(ms, "GSY", "14");
    }
    const auto v = f.finish(8000);
    EXPECT_EQ(has(v, top::Diagnosis::axis_left_moving), !stops) << stops;
    EXPECT_EQ(has(v, top::Diagnosis::refresh_gap), stops) << stops;
  }
}

// The motors stopped by the refresh limit 0.28 s before the end (topsim's
// C10, ReportKnownAnswers): the last mark's half second still held motion,
// and the axis read "still +5.9 deg/s at the end". Reports that read the
// same for the last 0.2 s are a stopped gimbal: refresh-gap, not left moving.
TEST(DiagnosesMotion, AStopJustBeforeTheEndIsNoAxisLeftMoving) {
  MotionFeed f(top::Dialect::skydroid);
  f.track.named(top::Model::c10);
  for (std::int64_t ms = 0; ms <= 3280; ms += 10) {
    const double yaw = static_cast<double>(std::clamp<std::int64_t>(ms - 1000, 0, 2000)) / 100;
    f.attitude(ms, "GAC", hex4(yaw) + "0000" + "0000");
    if (ms >= 1000 && ms <= 2000 && ms % 100 == 0) f.command(ms, "GSY", "14");
  }
  const auto v = f.finish(3280);
  EXPECT_FALSE(has(v, top::Diagnosis::axis_left_moving));
  EXPECT_TRUE(has(v, top::Diagnosis::refresh_gap));
}

// The model the device names (SkyDroid MOD "C13") is the model: an outside
// capture's report guessed "c12 (the device sent MOD, which the documents
// give to this model only)" of a device that answered MOD C13.
TEST(ReportModel, TheModelTheDeviceNamesIsTheModel) {
  report::ConvData c;
  c.models = top::model_bit(top::Model::c12);
  c.narrowed_by = "MOD";
  c.named = top::Model::c13;
  EXPECT_EQ(report::model_text(top::Model::unknown, top::Dialect::skydroid, &c),
            "c13 (named by the device's model-name reply)");
  EXPECT_EQ(report::model_text(top::Model::c20, top::Dialect::skydroid, &c), "c20 (given)");
}

// A serial log named `name` of twenty VER requests, 250 ms apart from
// 12:00:00, and no byte back, line `i` as `line(i, seconds, milliseconds)`
// writes it: whether the session reads a silent device in it.
bool names_silent_device(const std::string& name,
                         const std::function<std::string(int, int, int)>& line) {
  test::TempDir tmp;
  const std::string path = tmp.file(name);
  {
    std::ofstream o(path);
    for (int i = 0; i < 20; ++i) o << line(i, i / 4, (i % 4) * 250);
  }
  const test::Recorder r = test::read(path);
  return r.has_note(acode_of(top::Diagnosis::silent_device));
}

// A socat relay log records both directions by construction: requests with
// no byte back are a silent device, not a line nobody recorded (a raw
// dump's one tap). Found by an outside capture: nothing was named.
TEST(DiagnosesSession, SocatLogWithASilentDeviceNamesIt) {
  EXPECT_TRUE(names_silent_device("silent.log", [](int i, int s, int ms) {
    char head[96];
    std::snprintf(head, sizeof head,
                  "> 2024/05/01 12:00:%02d.%03d000000  length=16 from=%d to=%d\n", s, ms, i * 16,
                  i * 16 + 15);
    return std::string(head) + "#TPUD2rVER0051\\r\n";
  }));
}

// A line log names each line's direction: TX lines with no RX line are a
// silent device too (an outside capture named nothing).
TEST(DiagnosesSession, LineLogWithASilentDeviceNamesIt) {
  EXPECT_TRUE(names_silent_device("silent-lines.log", [](int, int s, int ms) {
    char line[96];
    std::snprintf(line, sizeof line, "2024-05-01T12:00:%02d.%03dZ TX #TPUD2rVER0051\n", s, ms);
    return std::string(line);
  }));
}

// A Snap copies a motion frame's data by fixed-size loads that stay within
// the data (issue 48: it read up to 8 bytes before a short datum, which
// every frame's header happened to hold): each length from 0 to 16, from a
// heap block of exactly that size, reads back as itself (an ASan build
// fails on a byte read outside it).
TEST(MotionSnap, CopiesTheDataFromWithinItAtEveryLength) {
  const top::MotionSpec* m = top::motion_of(top::Dialect::skydroid, "GSY");
  ASSERT_NE(m, nullptr);
  const top::FormSpec form{};
  for (std::size_t k = 0; k <= 16; ++k) {
    std::unique_ptr<char[]> block(new char[k == 0 ? 1 : k]);
    for (std::size_t i = 0; i < k; ++i) block[i] = static_cast<char>('A' + i);
    const std::string_view d(block.get(), k);
    diag::Snap s;
    ASSERT_TRUE(s.take(*m, &form, d, kT0)) << k;
    EXPECT_EQ(s.view(), d) << k;
    EXPECT_TRUE(s.same(*m, d)) << k;
    if (k > 0) {
      block[k - 1] = 'z';
      EXPECT_FALSE(s.same(*m, d)) << k;
    }
  }
}

}  // namespace
}  // namespace topdump
