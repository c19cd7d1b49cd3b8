// The diagnoses' detectors on their own (issue 29): each fed the frames or
// pushes the session would feed it, and the dates they read through the
// catalog's fields.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "diagnoses/baud_mismatch.hpp"
#include "diagnoses/clock_offset.hpp"
#include "diagnoses/refresh_gap.hpp"
#include "diagnoses/stream_never_started.hpp"
#include "diagnoses/stream_stalled.hpp"
#include "session/events.hpp"
#include "test_time.hpp"
#include "top/catalog.hpp"
#include "top/diagnoses.hpp"

namespace topdump {
namespace {

const top::FormSpec& date_form(top::Dialect d, std::string_view id, std::size_t len) {
  const top::CommandSpec* c = top::find_command(d, id);
  EXPECT_TRUE(c) << id;
  for (const top::FormSpec& f : c->forms)
    if (f.min_length <= len && len <= f.max_length) return f;
  ADD_FAILURE() << id << " has no form of length " << len;
  return c->forms.front();
}

TEST(DiagnosesRules, DatesReadByTheCatalogsFields) {
  // Topotek TIM: YYYYMMDDhhmmss; UTC: hhmmssDDMMYY; SkyDroid TIM (4.6
  // example): hhmmss.ssDDMMYY, 142832.00031218 = 2018-12-03 14:28:32
  auto t = top::date_time_of(date_form(top::Dialect::topotek, "TIM", 14), "20261126093005");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->year, 2026);
  EXPECT_EQ(t->month, 11);
  EXPECT_EQ(t->day, 26);
  EXPECT_EQ(t->second, 5);
  t = top::date_time_of(date_form(top::Dialect::topotek, "UTC", 12), "093005261126");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->year, 2026);
  EXPECT_EQ(t->month, 11);
  EXPECT_EQ(t->hour, 9);
  t = top::date_time_of(date_form(top::Dialect::skydroid, "TIM", 15), "142832.00031218");
  ASSERT_TRUE(t);
  EXPECT_EQ(top::epoch_seconds(*t), 1543847312);  // 2018-12-03T14:28:32Z
  EXPECT_FALSE(top::date_time_of(date_form(top::Dialect::topotek, "TIM", 14), "2026112609300x"));
  // month 0 is the December before
  EXPECT_EQ(top::epoch_seconds({2026, 0, 1, 0, 0, 0}), top::epoch_seconds({2025, 12, 1, 0, 0, 0}));
  EXPECT_EQ(top::epoch_seconds({1970, 1, 1, 0, 0, 0}), 0);
  // Two-digit years pivot as POSIX %y does: a SkyDroid TIM or Topotek UTC
  // of a camera that never set its clock reads 1970, not 2070 (found by an
  // outside capture: "2070-01-01 ... 15741 days late").
  t = top::date_time_of(date_form(top::Dialect::skydroid, "TIM", 15), "000512.00010170");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->year, 1970);
  t = top::date_time_of(date_form(top::Dialect::topotek, "UTC", 12), "000512010170");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->year, 1970);
  t = top::date_time_of(date_form(top::Dialect::topotek, "UTC", 12), "000512010168");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->year, 2068);
}

// ---- the detectors on their own ----------------------------------------------

// A steady 10 Hz stream asked for at 50 Hz is off its rate (stream-rate),
// never stalled: one cause, one item (issue 29, "Bugs found on the way").
TEST(DiagnosesStall, SlowSteadyStreamIsNoStall) {
  diag::StallWatch w;
  for (int i = 0; i < 300; ++i) w.push(static_cast<std::uint64_t>(i + 1), kT0 + i * 100'000, 50);
  EXPECT_FALSE(w.verdict("GAC", 1));
}

// The case's frame, time and end agree: the last push before the stall at
// its time, the end when the push resumed (an outside capture's JSON gave
// the resuming frame with the stop's time, and an `until` before its frame).
TEST(DiagnosesStall, TheCaseIsTheStopAndItsResumption) {
  diag::StallWatch w;
  std::uint64_t n = 0;
  std::int64_t t = kT0;
  for (int i = 0; i < 30; ++i) w.push(++n, t += 100'000, 10);
  const std::int64_t stop = t;
  for (int i = 0; i < 10; ++i) w.push(++n, t += (i == 0 ? 2'000'000 : 100'000), 10);
  const auto f = w.verdict("GAC", 1);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->c.dir, 1);  // the direction the stream is pushed in
  EXPECT_EQ(f->c.first_frame, 30u);
  EXPECT_EQ(f->c.first_ts, stop);
  EXPECT_EQ(f->c.last_ts, stop + 2'000'000);
  EXPECT_NE(f->figure.find("the first stopped after frame 30 and resumed at frame 31"),
            std::string::npos)
      << f->figure;
}

// A 50 Hz stream handed over in 100 ms bunches (Wi-Fi) is no stall, 73
// times over (an outside capture); a 300 ms stop of it is.
TEST(DiagnosesStall, LinkBunchesAreNoStall) {
  for (const std::int64_t gap_ms : {60, 100, 300}) {
    diag::StallWatch w;
    std::uint64_t n = 0;
    std::int64_t t = kT0;
    for (int i = 0; i < 50; ++i) w.push(++n, t += 20'000, 50);
    for (int bunch = 0; bunch < 20; ++bunch) {
      t += gap_ms * 1000;
      for (int i = 0; i < 5; ++i) w.push(++n, t += 1'000, 50);
    }
    EXPECT_EQ(w.verdict("GAC", 1).has_value(), gap_ms == 300) << gap_ms;
  }
}

TEST(DiagnosesStall, GapOfMoreThanThreePeriodsThatResumes) {
  diag::StallWatch w;
  std::uint64_t n = 0;
  for (int i = 0; i < 30; ++i) w.push(++n, kT0 + i * 100'000, 10);
  w.push(++n, kT0 + 29 * 100'000 + 2'000'000, 10);  // 2 s later
  for (int i = 1; i < 10; ++i) w.push(++n, kT0 + 49 * 100'000 + i * 100'000, 10);
  const auto f = w.verdict("GAC", 1);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->code, top::Diagnosis::stream_stalled);
  EXPECT_EQ(f->c.frames, 1u);
  EXPECT_EQ(f->c.first_frame, 30u);  // the last push before it
  EXPECT_EQ(f->c.first_ts, kT0 + 29 * 100'000);
  EXPECT_EQ(f->c.last_ts, kT0 + 49 * 100'000);  // resumed
  EXPECT_NE(f->figure.find("2.000 s"), std::string::npos) << f->figure;
  EXPECT_EQ(w.stalled_us(), 2'000'000);
}

TEST(DiagnosesStall, JitterWithinThreePeriodsIsNoStall) {
  diag::StallWatch w;
  std::int64_t t = kT0;
  for (int i = 0; i < 100; ++i) {
    t += (i % 5 == 0) ? 250'000 : 100'000;  // a late push now and then
    w.push(static_cast<std::uint64_t>(i + 1), t, 10);
  }
  EXPECT_FALSE(w.verdict("GAC", 1));
}

TEST(DiagnosesNeverStarted, NeedsAnAnsweredSwitchAndTime) {
  diag::NeverStartedWatch w;
  w.asked(1, kT0, "GAA");
  EXPECT_FALSE(w.verdict("GAC", 0, 10, kT0 + 5'000'000));  // never answered
  w.answered();
  EXPECT_FALSE(w.verdict("GAC", 0, 10, kT0 + 500'000));    // too soon to tell
  EXPECT_FALSE(w.verdict("GAC", 3, 10, kT0 + 5'000'000));  // it came
  const auto f = w.verdict("GAC", 0, 10, kT0 + 5'000'000);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->c.first_frame, 1u);
}

// What ClockWatch finds in Topotek TIM frames: {data, frame, time, dir,
// from the camera}.
struct TimFrame {
  const char* data;
  std::uint64_t n;
  std::int64_t ts;
  int dir;
  bool device;
};
std::optional<diag::Found> clock_verdict(std::initializer_list<TimFrame> frames) {
  const top::FormSpec& tim = date_form(top::Dialect::topotek, "TIM", 14);
  diag::ClockWatch w;
  for (const TimFrame& f : frames) w.frame(tim, f.data, "TIM", f.n, f.ts, f.dir, f.device);
  return w.verdict();
}

TEST(DiagnosesClock, OneMonthEarly1970AndTimeZones) {
  // Beijing time: 8 h ahead is no offset
  EXPECT_FALSE(clock_verdict({{"20240501200000", 1, kT0, 0, false}}));
  const auto early = clock_verdict({{"20240401120000", 7, kT0, 0, false}});
  ASSERT_TRUE(early);
  EXPECT_EQ(early->c.first_frame, 7u);
  EXPECT_NE(early->figure.find("exactly one month"), std::string::npos) << early->figure;
  EXPECT_NE(early->figure.find("0-based month sent unconverted"), std::string::npos);
  // the client's set is right, the camera's echo a month early: the
  // camera's clock, not the client's month (an outside capture's case)
  const auto echo = clock_verdict(
      {{"20240501120000", 15, kT0, 0, false}, {"20240401120000", 16, kT0 + 5000, 1, true}});
  ASSERT_TRUE(echo);
  EXPECT_EQ(echo->c.first_frame, 16u);
  EXPECT_NE(echo->figure.find("from the camera"), std::string::npos) << echo->figure;
  EXPECT_EQ(echo->figure.find("sent unconverted"), std::string::npos) << echo->figure;
  const auto unset = clock_verdict({{"19700101000512", 3, kT0, 1, true}});
  ASSERT_TRUE(unset);
  EXPECT_NE(unset->figure.find("1970: the camera's clock was never set"), std::string::npos)
      << unset->figure;
  // a serial log without times judges nothing
  EXPECT_FALSE(clock_verdict({{"19700101000512", 3, kNoTime, 1, true}}));
}

// Under two days the offset is in hours ("1 days late" read wrong for 25 h),
// and a date that is no day of the calendar is shown as sent: 31 March
// sent with a 0-based month reads 31 February, not 3 March (outside
// captures' cases).
TEST(DiagnosesClock, HoursAndDatesThatDoNotExist) {
  const auto hours = clock_verdict({{"20240502130000", 1, kT0, 0, false}});
  ASSERT_TRUE(hours);
  EXPECT_NE(hours->figure.find(": 25 hours late"), std::string::npos) << hours->figure;
  const auto days = clock_verdict({{"20240426000000", 1, kT0, 0, false}});
  ASSERT_TRUE(days);
  EXPECT_NE(days->figure.find(": 5.5 days early"), std::string::npos) << days->figure;
  const std::int64_t march31 = 1774958400LL * 1'000'000;  // 2026-03-31T12:00:00Z
  const auto feb31 = clock_verdict({{"20260231120000", 2, march31, 0, false}});
  ASSERT_TRUE(feb31);
  EXPECT_NE(feb31->figure.find("camera time 2026-02-31 (no such date: 2026-03-03 12:00:00)"),
            std::string::npos)
      << feb31->figure;
  EXPECT_NE(feb31->figure.find("exactly one month early"), std::string::npos) << feb31->figure;
}

TEST(DiagnosesBaud, TextNoiseIsNoBaudMismatch) {
  diag::BaudWatch text;
  text.garbage(200, "$GPGGA,123519,4807.038,N,01131.0", 1, kNoTime);
  EXPECT_FALSE(text.verdict());
  diag::BaudWatch binary;
  binary.garbage(200, "\xE8\xF7\x99\x9D \x08\xBD[\x08jF\xF9?\xBE\xCE\x08", 1, kNoTime);
  EXPECT_TRUE(binary.verdict());
}

// A serial line at the right speed that carries MAVLink (an autopilot port
// left on MAVLink) is binary too, but no mis-set speed: an outside capture
// of MAVLink v2 heartbeats and attitude read "the line speed is likely
// wrong" (error). Its packets chain, STX to STX; the same bytes shuffled
// do not, and a TOP line read at twice its speed still is named.
TEST(DiagnosesBaud, AMavlinkLineIsNoBaudMismatch) {
  std::string mav;
  std::uint32_t x = 12345;
  auto rnd = [&] { return static_cast<char>((x = x * 1103515245u + 12345u) >> 24); };
  for (int i = 0; i < 60; ++i) {
    const std::size_t len = i % 3 ? 28 : 9;  // ATTITUDE, HEARTBEAT
    mav += '\xFD';
    mav += static_cast<char>(len);
    mav += '\x00';  // unsigned
    for (std::size_t k = 0; k < 7 + len + 2; ++k) mav += rnd();
  }
  EXPECT_GE(diag::mavlink_chain(mav), 60 - 1);
  diag::BaudWatch line;
  line.bytes(mav);
  line.garbage(mav.size(), std::string_view(mav).substr(0, 32), 1, kNoTime);
  EXPECT_FALSE(line.verdict());

  std::string shuffled = mav;
  for (std::size_t i = 0; i < shuffled.size(); ++i) shuffled[i] = rnd();
  EXPECT_LT(diag::mavlink_chain(shuffled), diag::BaudWatch::kMavlinkChain);
  diag::BaudWatch noise;
  noise.bytes(shuffled);
  noise.garbage(shuffled.size(), std::string_view(shuffled).substr(0, 32), 1, kNoTime);
  EXPECT_TRUE(noise.verdict());
}

// The gap rules the report shares with stream-stalled and refresh-gap.
TEST(GapRules, MoreThanThreePeriodsAndMoreThanTheRefreshLimit) {
  EXPECT_EQ(diag::kGapPeriods, 3);
  EXPECT_FALSE(diag::stream_gap(300'000, 100'000));
  EXPECT_TRUE(diag::stream_gap(300'001, 100'000));
  EXPECT_FALSE(diag::refresh_missed(1'000'000, 1'000'000));
  EXPECT_TRUE(diag::refresh_missed(1'000'001, 1'000'000));
  EXPECT_FALSE(diag::refresh_missed(5'000'000, 0));  // no limit applies
}

}  // namespace
}  // namespace topdump
