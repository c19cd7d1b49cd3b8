// The diagnoses (issue 29): the table and its device rules, each detector on
// its own, and every bundled capture through the real topdump: each
// diag-CODE capture shows exactly its diagnosis, in read, stats and report,
// and no warning or error diagnosis fires on any other bundled capture.
#include "top/diagnoses.hpp"

#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "diagnoses/baud_mismatch.hpp"
#include "diagnoses/clock_offset.hpp"
#include "diagnoses/placeholder_identity.hpp"
#include "diagnoses/stream_never_started.hpp"
#include "diagnoses/stream_stalled.hpp"
#include "diagnoses/watch.hpp"
#include "findings/afindings.hpp"
#include "test_support.hpp"
#include "top/catalog.hpp"
#include "top/decode.hpp"
#include "top/frame.hpp"

namespace topdump {
namespace {

using test::captures_dir;
using test::run;
using test::slurp;
using test::topdump_bin;

constexpr std::int64_t kT0 = 1714564800LL * 1'000'000;  // 2024-05-01T12:00:00Z

// ---- the table ------------------------------------------------------------

TEST(DiagnosesTable, CodesAreStableDistinctAndDocumented) {
  const std::string doc = slurp(std::string(TOPKIT_SOURCE_DIR) + "/docs/DIAGNOSES.md");
  std::set<std::string_view> seen;
  for (std::size_t i = 0; i < top::diagnosis_count; ++i) {
    const auto d = static_cast<top::Diagnosis>(i);
    const std::string_view code = top::to_string(d);
    EXPECT_TRUE(seen.insert(code).second) << code;
    EXPECT_EQ(top::diagnosis_from_string(code), d);
    EXPECT_FALSE(top::title(d).empty()) << code;
    EXPECT_FALSE(top::evidence(d).empty()) << code;
    EXPECT_FALSE(top::remedy(d).empty()) << code;
    EXPECT_FALSE(top::finding_code_from_string(code)) << code << " is a frame finding's code";
    // the analyzer's code of the same name is this diagnosis
    const std::optional<ACode> a = acode_from_string(code);
    ASSERT_TRUE(a) << code;
    EXPECT_EQ(*a, acode_of(d));
    EXPECT_EQ(diagnosis_of(*a), d);
    EXPECT_EQ(default_severity(*a), top::severity(d));
    EXPECT_NE(doc.find("| `" + std::string(code) + "` |"), std::string::npos) << code;
  }
  EXPECT_FALSE(diagnosis_of(ACode::unanswered));
  EXPECT_EQ(top::diagnosis_from_string("unanswered"), std::nullopt);
}

// ---- the device rules -----------------------------------------------------

TEST(DiagnosesRules, PlaceholderIdentities) {
  for (const char* v :
       {"000000000", "0.0.0", "V0.0.0", "123", "1.2.3", "Unknown", "UNKNOWN", "", "   "})
    EXPECT_TRUE(top::is_placeholder_identity(v)) << v;
  for (const char* v : {"SIP-T1", "1.0.0", "SIM_TP", "M3326", "V1.0.0", "C13", "010502", "1230"})
    EXPECT_FALSE(top::is_placeholder_identity(v)) << v;
}

// SkyDroid MOD (the model name ArduPilot's driver reads) is an identity
// reply like VER: "Unknown" or zeros there are a placeholder (an outside
// capture's miss).
TEST(DiagnosesRules, SkyDroidModelNameIsAnIdentity) {
  EXPECT_TRUE(top::is_identity_reply(top::Dialect::skydroid, "MOD"));
  EXPECT_TRUE(top::is_identity_reply(top::Dialect::skydroid, "VER"));
  EXPECT_FALSE(top::is_identity_reply(top::Dialect::skydroid, "GAC"));
  for (const char* v : {"Unknown", "000000000"}) {
    diag::IdentityWatch w;
    w.reply(top::Dialect::skydroid, "MOD", v, 4, kT0, 1);
    const auto f = w.verdict();
    ASSERT_TRUE(f) << v;
    EXPECT_NE(f->figure.find("MOD"), std::string::npos) << f->figure;
  }
  diag::IdentityWatch ok;
  ok.reply(top::Dialect::skydroid, "MOD", "C13", 4, kT0, 1);
  EXPECT_FALSE(ok.verdict());
}

TEST(DiagnosesRules, TrackingRefusedIsState4Only) {
  EXPECT_TRUE(top::refuses_tracking(top::Dialect::topotek, "TRC", "04"));
  EXPECT_FALSE(top::refuses_tracking(top::Dialect::topotek, "TRC", "03"));  // temporarily lost
  EXPECT_FALSE(top::refuses_tracking(top::Dialect::topotek, "TRC", "02"));
  EXPECT_FALSE(top::refuses_tracking(top::Dialect::skydroid, "TRC", "04"));
}

// carries_date() names every identifier whose catalog form has a date.
TEST(DiagnosesRules, CarriesDateMatchesTheCatalog) {
  for (top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek})
    for (const top::CommandSpec& c : top::commands(d))
      for (const top::FormSpec& f : c.forms) {
        bool year = false;
        for (const top::FieldSpec& x : f.fields) year |= x.name == "year";
        if (year) {
          EXPECT_TRUE(top::carries_date(c.ident)) << c.ident;
        }
      }
}

// The session's prefilter lets through every frame a detector's rule
// could take: the decoded frame says so (Decoded::diagnosed), with and
// without the shape cache (topdump stats), for either sender.
TEST(DiagnosesRules, WatchPrefilterCoversTheRules) {
  top::DecodeCache cache;
  std::size_t ruled_count = 0;
  for (top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek})
    for (const top::CommandSpec& c : top::commands(d)) {
      const std::string id(c.ident);
      const bool ruled = top::is_identity_reply(d, id) || top::carries_date(id) ||
                         top::refuses_tracking(d, id, "04") ||
                         top::reports_tracking(d, id, 'r', "02");
      EXPECT_EQ(top::may_matter_to_diagnoses(id.c_str()), ruled) << id;
      ruled_count += ruled;
      for (top::Role role : {top::Role::request, top::Role::response}) {
        top::BuildSpec b;
        b.src = role == top::Role::request ? 'U' : c.address;
        b.dst = role == top::Role::request ? c.address : 'U';
        b.control = 'r';
        b.ident = c.ident;
        b.data = "00";
        const top::ParseResult r = top::parse_frame(top::build_frame(b), true);
        ASSERT_EQ(r.status, top::ParseStatus::frame) << id;
        for (top::DecodeCache* cached : {static_cast<top::DecodeCache*>(nullptr), &cache}) {
          top::DecodeOptions o{d, top::Model::unknown, role};
          o.detail = cached == nullptr;
          o.cache = cached;
          for (int pass = 0; pass < 2; ++pass)  // the second from the cache
            EXPECT_EQ(top::decode(r.frame, o).diagnosed, ruled) << id << " pass " << pass;
        }
      }
    }
  EXPECT_GE(ruled_count, 7u);  // PA2, VSN, VER, MOD, TRC, TIM, UTC across the two
}

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
  EXPECT_FALSE(w.verdict("GAC"));
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
    EXPECT_EQ(w.verdict("GAC").has_value(), gap_ms == 300) << gap_ms;
  }
}

TEST(DiagnosesStall, GapOfMoreThanThreePeriodsThatResumes) {
  diag::StallWatch w;
  std::uint64_t n = 0;
  for (int i = 0; i < 30; ++i) w.push(++n, kT0 + i * 100'000, 10);
  w.push(++n, kT0 + 29 * 100'000 + 2'000'000, 10);  // 2 s later
  for (int i = 1; i < 10; ++i) w.push(++n, kT0 + 49 * 100'000 + i * 100'000, 10);
  const auto f = w.verdict("GAC");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->code, top::Diagnosis::stream_stalled);
  EXPECT_EQ(f->c.frames, 1u);
  EXPECT_EQ(f->c.first_frame, 31u);
  EXPECT_EQ(f->c.first_ts, kT0 + 29 * 100'000);
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
  EXPECT_FALSE(w.verdict("GAC"));
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

// ---- every bundled capture through topdump ---------------------------------

// The warning and error diagnoses `topdump read --json` reports, by code,
// with the exit status.
struct Seen {
  std::map<std::string, nlohmann::json> diagnoses;
  int status = 0;
};

Seen read_json(const std::string& file, const std::string& extra = "") {
  std::string out;
  Seen s;
  s.status = run("cd '" + captures_dir() + "' && '" + topdump_bin() + "' read --json " + extra +
                     " '" + file + "' 2>/dev/null",
                 out);
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    const auto j = nlohmann::json::parse(line);
    if (j["type"] != "finding") continue;
    const std::string code = j["code"];
    if (top::diagnosis_from_string(code) && j["severity"] != "info") s.diagnoses[code] = j;
  }
  return s;
}

// Each diag-CODE capture: exactly its diagnosis, with its case.
TEST(DiagnosesCaptures, EachFiresOnItsCapture) {
  const std::map<std::string, std::string> made = {
      {"diag-stream-stalled.pcap", "stream-stalled"},
      {"diag-stream-never-started.pcap", "stream-never-started"},
      {"diag-placeholder-identity.pcap", "placeholder-identity"},
      {"diag-tracking-refused.pcap", "tracking-refused"},
      {"diag-clock-offset.pcap", "clock-offset"},
      {"diag-reply-interface.pcap", "reply-interface"},
      {"diag-silent-device.pcap", "silent-device"},
      {"diag-dropped-bad-checksum.log", "dropped-bad-checksum"},
      {"diag-dropped-checksum-case.log", "dropped-checksum-case"},
      {"diag-baud-mismatch.bin", "baud-mismatch"},
      {"diag-direction-inverted.pcap", "direction-inverted"},
      {"diag-command-ignored.log", "command-ignored"},
      {"diag-attitude-stale.pcap", "attitude-stale"},
      {"diag-axis-left-moving.log", "axis-left-moving"},
      {"diag-stream-rate.pcap", "stream-rate"},
      {"diag-refresh-gap.pcap", "refresh-gap"},
  };
  for (const auto& [file, code] : made) {
    const Seen s = read_json(file);
    ASSERT_EQ(s.diagnoses.size(), 1u) << file;
    ASSERT_TRUE(s.diagnoses.count(code)) << file << ": " << s.diagnoses.begin()->first;
    const auto& j = s.diagnoses.at(code);
    EXPECT_EQ(s.status, 1) << file;
    EXPECT_GE(j["count"].get<int>(), 1) << file;
    EXPECT_FALSE(j["evidence"].get<std::string>().empty()) << file;
    EXPECT_FALSE(j["remedy"].get<std::string>().empty()) << file;
    if (code != "baud-mismatch") {
      EXPECT_TRUE(j["frame"].is_number()) << file;
      EXPECT_TRUE(j["conversation"].is_number()) << file;
    }
    // --mute CODE takes it out, and with it the exit status it caused
    const Seen muted = read_json(file, "--mute " + code);
    EXPECT_EQ(muted.diagnoses.count(code), 0u) << file;
  }
}

// The figures the issue asks for, measured.
// The finding selection applies to diagnoses: identifier and time.
TEST(DiagnosesCaptures, SelectedByIdentAndTime) {
  EXPECT_EQ(read_json("diag-tracking-refused.pcap", "--ident TRC").diagnoses.size(), 1u);
  const Seen other = read_json("diag-tracking-refused.pcap", "--ident VSN");
  EXPECT_TRUE(other.diagnoses.empty());
  EXPECT_EQ(other.status, 0);
  // the stall began at 12:00:03
  EXPECT_EQ(read_json("diag-stream-stalled.pcap", "--to 2024-05-01T12:00:02Z").diagnoses.size(),
            0u);
  EXPECT_EQ(read_json("diag-stream-stalled.pcap", "--from 2024-05-01T12:00:02Z").diagnoses.size(),
            1u);
}

TEST(DiagnosesCaptures, CarryTheirMeasuredFigure) {
  struct Figure {
    const char* file;
    const char* code;
    const char* text;  // in its message
  };
  const Figure figures[] = {
      {"diag-clock-offset.pcap", "clock-offset",
       "camera time 2024-04-01 20:00:00, capture 2024-05-01 12:00:00: exactly one month early"},
      {"diag-placeholder-identity.pcap", "placeholder-identity", "\"000000000\""},
      {"diag-stream-stalled.pcap", "stream-stalled", "longest 2.100 s"},
      {"diag-reply-interface.pcap", "reply-interface", "5 requests"},
      // the motion diagnoses: commanded against measured
      {"diag-direction-inverted.pcap", "direction-inverted",
       "GSP 20 (10.0 deg/s up): pitch moved -9.5 deg/s (down)"},
      {"diag-command-ignored.log", "command-ignored",
       "GAY to +30.0 deg was acknowledged; yaw stayed at +0.0 deg"},
      {"diag-attitude-stale.pcap", "attitude-stale", "20 non-zero motion commands"},
      {"diag-axis-left-moving.log", "axis-left-moving",
       "yaw moved +49.0 deg in the 4.850 s to the end"},
  };
  for (const Figure& f : figures) {
    const Seen s = read_json(f.file);
    if (!s.diagnoses.count(f.code)) {  // the next captures are checked still
      ADD_FAILURE() << f.file << ": no " << f.code;
      continue;
    }
    const std::string message = s.diagnoses.at(f.code)["message"].get<std::string>();
    EXPECT_NE(message.find(f.text), std::string::npos) << f.file << ": " << message;
  }
}

// A motion diagnosis names its axis (the JSON's `axis`), and none where a
// diagnosis has no axis.
TEST(DiagnosesCaptures, MotionDiagnosesNameTheirAxis) {
  auto axis = [](const char* file, const char* code) {
    const Seen s = read_json(file);
    return s.diagnoses.count(code) ? s.diagnoses.at(code)["axis"] : nlohmann::json("missing");
  };
  EXPECT_EQ(axis("diag-direction-inverted.pcap", "direction-inverted"), "pitch");
  EXPECT_EQ(axis("diag-command-ignored.log", "command-ignored"), "yaw");
  EXPECT_EQ(axis("diag-axis-left-moving.log", "axis-left-moving"), "yaw");
  EXPECT_TRUE(axis("diag-attitude-stale.pcap", "attitude-stale").is_null());
}

// No warning or error diagnosis on any other bundled capture, except the
// ones they were made to show before diagnoses existed (sample.pcap's
// dropped bad-checksum GAY; ipv6.pcap's and the socat logs' stream-rate).
TEST(DiagnosesCaptures, SilentOnEveryOtherCapture) {
  const std::map<std::string, std::set<std::string>> known = {
      {"sample.pcap", {"dropped-bad-checksum"}},
      {"ipv6.pcap", {"stream-rate"}},
      {"serial-socat-v.log", {"stream-rate"}},
      {"serial-socat-xv.log", {"stream-rate"}},
  };
  std::string listing;
  run("cd '" + captures_dir() + "' && ls *.pcap *.pcapng *.bin *.log *.csv", listing);
  std::istringstream in(listing);
  std::string file;
  int checked = 0;
  while (std::getline(in, file)) {
    if (file.rfind("diag-", 0) == 0 && file.rfind("diag-healthy-", 0) != 0) continue;
    const Seen s = read_json(file);
    std::set<std::string> codes;
    for (const auto& [c, j] : s.diagnoses) codes.insert(c);
    const auto k = known.find(file);
    EXPECT_EQ(codes, k == known.end() ? std::set<std::string>{} : k->second) << file;
    ++checked;
  }
  EXPECT_GE(checked, 19);
}

TEST(DiagnosesCaptures, CountedByStatsAndItemsOfTheReport) {
  std::string out;
  run("cd '" + captures_dir() + "' && '" + topdump_bin() +
          "' stats --json diag-tracking-refused.pcap",
      out);
  const auto st = nlohmann::json::parse(out);
  EXPECT_EQ(st["per_finding"]["tracking-refused"], 1) << out;
  run("cd '" + captures_dir() + "' && '" + topdump_bin() + "' stats diag-stream-stalled.pcap", out);
  EXPECT_NE(out.find("stream-stalled 1"), std::string::npos) << out;

  const int rc = run("cd '" + captures_dir() + "' && '" + topdump_bin() +
                         "' report --json -o - diag-stream-stalled.pcap",
                     out);
  EXPECT_EQ(rc, 1);
  const auto r = nlohmann::json::parse(out);
  int stalled = 0, gaps = 0;
  for (const auto& w : r["overview"]["what_went_wrong"]) {
    if (w["code"] == "stream-stalled") {
      ++stalled;
      EXPECT_EQ(w["frame"], 43);
      EXPECT_EQ(w["evidence"], std::string(top::evidence(top::Diagnosis::stream_stalled)));
      EXPECT_EQ(w["remedy"], std::string(top::remedy(top::Diagnosis::stream_stalled)));
    }
    // one cause, one item: no stream-rate for the stall, no second gap item
    EXPECT_NE(w["code"], "stream-rate") << w;
    gaps += w["text"].get<std::string>().find("push stopped") != std::string::npos;
  }
  EXPECT_EQ(stalled, 1) << out;
  EXPECT_EQ(gaps, 1) << out;
}

}  // namespace
}  // namespace topdump
