// topconf drive's grading on records made by hand (docs/DRIVE.md): each
// check passes on what a good driver does and fails on the known bug, so
// that no check is one that cannot fail; the case table's IDs are stable.
#include <gtest/gtest.h>

#include "drive/grade.hpp"
#include "top/frame.hpp"

namespace {

using namespace topconf::drive;

const CaseSpec& spec(const char* id) {
  const CaseSpec* c = find_case(id);
  EXPECT_NE(c, nullptr) << id;
  return *c;
}

Verdict grade(const char* id, const Record& r, top::Model m = top::Model::c12) {
  const CaseSpec& c = spec(id);
  return grade_case(c, setup_case(c, m, topsim::TransportKind::udp, false), m,
                    topsim::TransportKind::udp, r);
}

WireFrame push(double t) {
  WireFrame w;
  w.t = t;
  w.attitude = true;
  w.ident = "GAC";
  return w;
}
WireFrame rate(double t, double yaw, double pitch = 0) {
  WireFrame w;
  w.t = t;
  w.from_driver = true;
  w.rate = true;
  w.axis = {true, true, false};
  w.value = {yaw, pitch, 0};
  return w;
}
Belief belief(double t, double pitch, bool healthy = true) {
  return Belief{t,
                {{"attitude", {{"yaw", 0}, {"pitch", pitch}, {"roll", 0}}}, {"healthy", healthy}}};
}

TEST(DriveCases, StableIds) {
  std::vector<std::string> ids;
  for (const CaseSpec& c : cases()) ids.emplace_back(c.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"1.1", "1.2", "1.3", "1.4", "2.1", "2.2", "2.3",
                                           "2.4", "2.5", "3.1", "3.2", "3.3", "3.4", "4.1",
                                           "5.1", "6.1", "6.2", "6.3", "6.4", "6.5", "7.1",
                                           "7.2", "7.3", "8.1", "8.2", "8.3", "9.1"}));
  std::string err;
  EXPECT_EQ(select_cases({"2"}, err).size(), 5u);
  EXPECT_TRUE(select_cases({"2.9"}, err).empty());
  EXPECT_NE(err.find("2.9"), std::string::npos);
}

// 2.5: rates on an attitude older than 1.2 s fail, on a fresh one pass.
TEST(DriveGrade, RatesOnAStaleAttitude) {
  Record r;
  r.duration_s = 4.5;
  for (double t = 0.2; t < 1.0; t += 0.1) r.wire.push_back(push(t));
  for (double t = 3.2; t < 4.5; t += 0.1) r.wire.push_back(push(t));
  r.wire.push_back(rate(0.6, 10));
  Record good = r;
  good.wire.push_back(rate(3.5, 10));
  EXPECT_EQ(grade("2.5", good).grade, Grade::pass);
  Record bad = r;
  bad.wire.push_back(rate(2.5, 10));
  const Verdict v = grade("2.5", bad);
  EXPECT_EQ(v.grade, Grade::fail) << v.reason;
  EXPECT_NE(v.reason.find("2.50 s"), std::string::npos) << v.reason;
  Record none;
  none.duration_s = 4.5;
  EXPECT_EQ(grade("2.5", none).grade, Grade::unimplemented);
}

// 2.4: per axis; a zero pitch beside a turning yaw stops nothing.
TEST(DriveGrade, StopAfterTheLastRate) {
  Record r;
  r.duration_s = 2.2;
  r.intents = {Intent{0.5, {{"do", "rate"}}}, Intent{1.2, {{"do", "stop"}}}};
  for (double t = 0.5; t < 1.2; t += 0.05) r.wire.push_back(rate(t, 10, 0));
  Record bad = r;
  bad.wire.push_back(rate(1.25, 10, 0));
  WireFrame pitch_only = rate(1.3, 0, 0);
  pitch_only.axis = {false, true, false};
  bad.wire.push_back(pitch_only);
  EXPECT_EQ(grade("2.4", bad).grade, Grade::fail);
  Record good = r;
  good.wire.push_back(rate(1.25, 0, 0));
  EXPECT_EQ(grade("2.4", good).grade, Grade::pass) << grade("2.4", good).reason;
  Record late = good;
  late.wire.push_back(rate(1.9, 10, 0));
  EXPECT_EQ(grade("2.4", late).grade, Grade::fail);
}

// The belief checks (6.x, 7.x, 2.3): off by more than 2 deg fails, an
// unhealthy belief is allowed, no belief is unimplemented.
TEST(DriveGrade, BeliefsAgainstTheTruth) {
  Record r;
  r.duration_s = 3;
  for (double t = 0; t < 3; t += 0.05) {
    Truth x;
    x.t = t;
    x.angle = {0, t > 1 ? 10.0 : 0.0, 0};
    r.truth.push_back(x);
  }
  EXPECT_EQ(grade("7.1", r).grade, Grade::unimplemented);
  Record good = r;
  good.beliefs = {belief(0.8, 0.5), belief(1.5, 10.5), belief(2.0, 99, false)};
  EXPECT_EQ(grade("7.1", good).grade, Grade::pass) << grade("7.1", good).reason;
  Record bad = r;
  bad.beliefs = {belief(0.8, 0), belief(2.0, -6)};
  const Verdict v = grade("7.1", bad);
  EXPECT_EQ(v.grade, Grade::fail);
  EXPECT_NE(v.reason.find("pitch -6.0"), std::string::npos) << v.reason;
}

// 3.2: the version right, unknown (non-strict) or wrong.
TEST(DriveGrade, VersionBelief) {
  Record r;
  r.duration_s = 3;
  r.version = "123";
  for (double t = 0.2; t < 3; t += 0.1) r.wire.push_back(push(t));
  r.intents = {Intent{1.0, {{"do", "rate"}}}, Intent{1.8, {{"do", "stop"}}}};
  r.wire.push_back(rate(1.1, 0, 10));
  for (const auto& [said, want] :
       std::vector<std::pair<std::string, Grade>>{{"123", Grade::pass},
                                                  {"1.2.3", Grade::pass},
                                                  {"unknown", Grade::non_strict},
                                                  {"123.0.0", Grade::fail},
                                                  {"1.6.26", Grade::fail}}) {
    Record x = r;
    x.beliefs = {Belief{2.0, {{"version", said}}}};
    EXPECT_EQ(grade("3.2", x, top::Model::sip).grade, want) << said;
  }
}

// 9.1: the clock write's month from the frame, 1-based.
TEST(DriveGrade, ClockMonth) {
  for (const auto& [data, want] : std::vector<std::pair<std::string, Grade>>{
           {"120000.00061226", Grade::pass}, {"120000.00061126", Grade::fail}}) {
    Record r;
    r.duration_s = 3;
    WireFrame w;
    w.t = 0.3;
    w.from_driver = true;
    w.control = 'w';
    w.ident = "TIM";
    w.data = data;
    w.raw = top::build_frame(top::BuildSpec{.header = top::Header::variable,
                                            .src = 'U',
                                            .dst = 'D',
                                            .control = 'w',
                                            .ident = "TIM",
                                            .data = data});
    r.wire.push_back(w);
    EXPECT_EQ(grade("9.1", r).grade, want) << data;
  }
  Record none;
  EXPECT_EQ(grade("9.1", none).grade, Grade::unimplemented);
}

// Cases that do not apply are informational, with the reason.
TEST(DriveGrade, NotApplicable) {
  const Verdict v = grade("6.4", Record{});
  EXPECT_EQ(v.grade, Grade::informational);
  EXPECT_NE(v.reason.find("SkyDroid"), std::string::npos);
  EXPECT_EQ(exit_code_of({Grade::pass, Grade::informational, Grade::unimplemented}), 0);
  EXPECT_EQ(exit_code_of({Grade::pass, Grade::fail}), 1);
  EXPECT_EQ(exit_code_of({Grade::fail, Grade::error}), 2);
}

}  // namespace
