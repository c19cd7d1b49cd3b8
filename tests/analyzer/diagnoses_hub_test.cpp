// The detectors the session used to decide for itself (issue 48): the
// silent stretch, stream-rate and the dropped requests, each on its own, fed
// what the session feeds them; the registry against the table; the JSON
// document's list of diagnoses against the table.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "diagnoses/cause.hpp"
#include "diagnoses/dropped_requests.hpp"
#include "diagnoses/registry.hpp"
#include "diagnoses/silent_device.hpp"
#include "diagnoses/stream_rate.hpp"
#include "test_support.hpp"
#include "test_time.hpp"
#include "top/diagnoses.hpp"

namespace topdump {
namespace {

TEST(DiagnosesHub, EveryRowOfTheTableHasOneDetector) {
  for (std::size_t i = 0; i < top::diagnosis_count; ++i) {
    const auto d = static_cast<top::Diagnosis>(i);
    EXPECT_EQ(diag::deciders_of(d), 1u) << top::to_string(d);
  }
}

TEST(DiagnosesHub, TheJsonDocumentListsTheTablesCodesInItsOrder) {
  const std::string doc = test::slurp(std::string(TOPKIT_SOURCE_DIR) + "/docs/topdump-json.md");
  const std::string from = "`protocol/include/top/diagnoses.hpp`: ";
  const std::size_t a = doc.find(from);
  ASSERT_NE(a, std::string::npos);
  const std::size_t b = doc.find(") are finding events", a);
  ASSERT_NE(b, std::string::npos);
  std::vector<std::string> listed;
  for (std::size_t i = doc.find('`', a + from.size()); i < b; i = doc.find('`', i + 1)) {
    const std::size_t j = doc.find('`', i + 1);
    listed.push_back(doc.substr(i + 1, j - i - 1));
    i = j;
  }
  std::vector<std::string> table;
  for (std::size_t i = 0; i < top::diagnosis_count; ++i)
    table.emplace_back(top::to_string(static_cast<top::Diagnosis>(i)));
  EXPECT_EQ(listed, table);
}

TEST(DiagnosesHub, FourCausesAreDiagnoses) {
  EXPECT_EQ(diagnosis_of(Cause::bad_checksum), top::Diagnosis::dropped_bad_checksum);
  EXPECT_EQ(diagnosis_of(Cause::checksum_case), top::Diagnosis::dropped_checksum_case);
  EXPECT_EQ(diagnosis_of(Cause::uart_source), top::Diagnosis::reply_interface);
  EXPECT_EQ(diagnosis_of(Cause::silent), top::Diagnosis::silent_device);
  for (Cause c : {Cause::none, Cause::unsupported, Cause::invalid, Cause::other_port})
    EXPECT_FALSE(diagnosis_of(c)) << describe(c);
  for (std::size_t i = 1; i < cause_count; ++i)
    EXPECT_FALSE(describe(static_cast<Cause>(i)).empty()) << i;
}

TEST(SilentDevice, SeveralRequestsOneTimedOut) {
  diag::SilentStretch s;
  s.add(3, kT0, "GAC", 0, false);
  EXPECT_FALSE(s.verdict()) << "one request is no silence";
  s.add(7, kT0 + 1'000'000, "VER", 0, false);
  EXPECT_FALSE(s.verdict()) << "cut off by the capture's end, not timed out";
  s.add(9, kT0 + 4'000'000, "GAC", 0, true);
  const auto f = s.verdict();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->code, top::Diagnosis::silent_device);
  EXPECT_EQ(f->c.first_frame, 3u);
  EXPECT_EQ(f->c.frames, 3u);
  EXPECT_EQ(f->c.last_ts, kT0 + 4'000'000);
  EXPECT_EQ(s.idents(), "GAC, VER");
  EXPECT_EQ(f->figure,
            "the device was silent: 3 requests (GAC, VER) from frame 3 to frame 9 over 4.000 s "
            "got no response");
}

diag::StreamRun run(double asked, std::uint64_t frames, std::int64_t span_us) {
  diag::StreamRun r{"GAC", "GAA", asked, frames, kT0, kT0 + span_us};
  r.first_push = 11;
  r.dir = 1;
  return r;
}

TEST(StreamRate, OffByMoreThanTheToleranceOnly) {
  // 101 pushes over 10 s: 10 Hz
  EXPECT_FALSE(diag::StreamRate::verdict(run(10, 101, 10'000'000)));
  EXPECT_FALSE(diag::StreamRate::verdict(run(12.5, 101, 10'000'000)));  // 20% off
  const auto f = diag::StreamRate::verdict(run(20, 101, 10'000'000));   // 50% off
  ASSERT_TRUE(f);
  EXPECT_EQ(f->code, top::Diagnosis::stream_rate);
  EXPECT_EQ(f->c.first_frame, 11u);
  EXPECT_EQ(f->c.frames, 101u);
  EXPECT_EQ(f->c.dir, 1);
  EXPECT_EQ(f->figure, "GAC stream runs at 10.0 Hz, GAA asked for 20 Hz (101 frames)");
  EXPECT_FALSE(diag::StreamRate::verdict(run(0, 101, 10'000'000))) << "no rate asked";
  EXPECT_FALSE(diag::StreamRate::verdict(run(20, 1, 0))) << "one push";
}

TEST(StreamRate, AStallIsTheCauseWhenTheRestRanAtTheRateAsked) {
  // 101 pushes at 20 Hz (5 s) and a 5 s stall: 10 Hz over 10 s
  diag::StreamRun r = run(20, 101, 10'000'000);
  r.stalled = true;
  r.stalled_us = 5'000'000;
  EXPECT_FALSE(diag::StreamRate::verdict(r));
  r.stalled_us = 1'000'000;  // 101 pushes over 9 s: still off
  EXPECT_TRUE(diag::StreamRate::verdict(r));
  EXPECT_DOUBLE_EQ(diag::measured_hz(101, kT0, kT0 + 10'000'000), 10.0);
  EXPECT_EQ(diag::measured_hz(1, kT0, kT0), 0.0);
}

TEST(DroppedRequests, CausesDecideWhichCaseARequestJoins) {
  diag::DroppedWatch w;
  w.request(Cause::uart_source, 1, kT0, "GAC", 0);      // the client's deviation
  w.request(Cause::bad_checksum, 2, kT0, "GAC", 0);     // not dropped until unanswered
  w.unanswered(Cause::bad_checksum, 2, kT0, "GAC", 0);  // dropped
  w.unanswered(Cause::uart_source, 1, kT0, "GAC", 0);   // counted
  w.unanswered(Cause::invalid, 3, kT0, "GAC", 0);       // no diagnosis
  std::vector<top::Diagnosis> found;
  w.verdicts([&](diag::Found f) { found.push_back(f.code); });
  EXPECT_EQ(found, (std::vector<top::Diagnosis>{top::Diagnosis::reply_interface,
                                                top::Diagnosis::dropped_bad_checksum}));
  const auto f = w.verdict(top::Diagnosis::reply_interface);
  ASSERT_TRUE(f);
  EXPECT_NE(f->figure.find(": 1 got no answer"), std::string::npos) << f->figure;
  EXPECT_FALSE(w.verdict(top::Diagnosis::silent_device));
}

}  // namespace
}  // namespace topdump
