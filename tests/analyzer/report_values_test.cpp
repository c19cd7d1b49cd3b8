// The report decides by values (issue 48, "Values between rooms"): the
// unanswered requests grouped by cause and identifier in the order the
// report has always had, the causes that are diagnoses left to them
// (diagnosis_of), finding codes left out by their code, the
// speed-unit verdict, and the time of day from the time.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "diagnoses/cause.hpp"
#include "report/analysis.hpp"
#include "report/report.hpp"
#include "test_time.hpp"

namespace topdump {
namespace {

constexpr auto kLastCause = Cause::silent;

std::vector<Cause> every_cause() {
  std::vector<Cause> v;
  for (int i = 0; i <= static_cast<int>(kLastCause); ++i) v.push_back(static_cast<Cause>(i));
  return v;
}

// Every cause is either a diagnosis or listed among the unanswered
// requests, never both, never neither.
TEST(ReportFacts, EveryCauseIsListedOrADiagnosis) {
  for (Cause c : every_cause())
    EXPECT_NE(diagnosis_of(c).has_value(), report::unanswered_rank(c).has_value())
        << static_cast<int>(c);
}

// The report once grouped unanswered requests by the causes' text (a
// std::map keyed by identifier and text): the order of the causes it now
// ranks by value is that order, so its output stays as it was.
TEST(ReportFacts, TheCausesComeInTheOrderOfTheirTextAsThey) {
  const auto& o = report::kUnansweredOrder;
  EXPECT_EQ(
      std::vector<Cause>(o.begin(), o.end()),
      (std::vector<Cause>{Cause::none, Cause::other_port, Cause::unsupported, Cause::invalid}));
  EXPECT_TRUE(std::is_sorted(o.begin(), o.end(),
                             [](Cause a, Cause b) { return describe(a) < describe(b); }));
  for (std::size_t i = 0; i < o.size(); ++i) EXPECT_EQ(report::unanswered_rank(o[i]), i);
}

// The facts as the report wrote them when it grouped by text: a map keyed
// by identifier, "\x01" and the cause's text, a cause that is a diagnosis
// left out, then ranked.
std::vector<std::string> facts_grouped_by_text(const report::ReportSink& d) {
  struct Group {
    std::uint64_t n = 0;
    std::int64_t first = kNoTime, last = kNoTime;
    std::string text;
  };
  std::map<std::string, Group> groups;
  for (const auto& u : d.unanswered) {
    if (u.cause == Cause::silent || u.cause == Cause::bad_checksum ||
        u.cause == Cause::checksum_case || u.cause == Cause::uart_source)
      continue;
    const std::string cause(describe(u.cause));
    Group& g = groups[u.ident + "\x01" + cause];
    ++g.n;
    if (g.first == kNoTime) g.first = u.ts;
    g.last = u.ts;
    g.text = cause.empty() ? "no response" : cause;
  }
  std::vector<std::pair<int, std::string>> ranked;
  for (const auto& [k, g] : groups)
    ranked.emplace_back(g.text == "no response" ? 80 : 60,
                        std::to_string(g.n) + " " + k.substr(0, 3) +
                            (g.n == 1 ? " request unanswered at " + report::clock_text(g.first)
                                      : " requests unanswered from " + report::clock_text(g.first) +
                                            " to " + report::clock_text(g.last)) +
                            ": " + g.text);
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<std::string> v;
  for (auto& r : ranked) v.push_back(std::move(r.second));
  return v;
}

TEST(ReportFacts, UnansweredGroupsComeByIdentifierThenCauseAsTheyDid) {
  report::ReportSink d;
  std::int64_t t = kT0;
  for (const char* ident : {"GAC", "ABC", "ZZZ", "GA0"})
    for (Cause c : every_cause())
      for (int k = 0; k < 1 + static_cast<int>(c) % 2; ++k)
        d.unanswered.push_back({t += 250'000, 1, 1, "f.pcap", "message", ident, c});
  report::Report rep;
  report::facts(d, rep);
  std::vector<std::string> got;
  for (const report::Fact& f : rep.facts) {
    if (f.anchor != "unanswered") continue;
    got.push_back(f.text);
    EXPECT_EQ(f.severity, f.text.find("another port") != std::string::npos ? top::Severity::info
                                                                           : top::Severity::warning)
        << f.text;
  }
  EXPECT_EQ(got, facts_grouped_by_text(d));
  ASSERT_EQ(got.size(), 16u);
  // no cause first (ranked higher), then per identifier other port,
  // unsupported, invalid
  EXPECT_EQ(got[0].substr(0, 6), "1 ABC ");
  EXPECT_NE(got[0].find("no response"), std::string::npos);
  EXPECT_EQ(got[4].substr(0, 6), "1 ABC ");
  EXPECT_NE(got[4].find(describe(Cause::other_port)), std::string::npos);
  EXPECT_NE(got[5].find(describe(Cause::unsupported)), std::string::npos);
  EXPECT_NE(got[6].find(describe(Cause::invalid)), std::string::npos);
  EXPECT_EQ(got[7].substr(0, 6), "1 GA0 ");
}

// Unanswered requests and diagnoses have facts of their own: their codes
// (analyzer codes) are left out of the findings' facts by value.
TEST(ReportFacts, CodeFactsLeaveOutUnansweredAndDiagnosesByTheirCode) {
  report::ReportSink d;
  auto code = [&](std::string name, std::optional<ACode> a, top::Severity s) {
    report::CodeStat& c = d.codes[name];
    c.code = name;
    c.acode = a;
    c.severity = s;
    c.count = 2;
    c.first = kT0;
    c.last = kT0 + 1000;
  };
  code("unanswered", ACode::unanswered, top::Severity::warning);
  code("silent-device", acode_of(top::Diagnosis::silent_device), top::Severity::warning);
  code("dropped-bad-checksum", acode_of(top::Diagnosis::dropped_bad_checksum),
       top::Severity::error);
  code("tcp-gap", ACode::tcp_gap, top::Severity::error);
  code("bad-checksum", std::nullopt, top::Severity::error);
  report::Report rep;
  report::facts(d, rep);
  std::vector<std::string> anchors;
  for (const report::Fact& f : rep.facts) anchors.push_back(f.anchor);
  std::sort(anchors.begin(), anchors.end());
  EXPECT_EQ(anchors, (std::vector<std::string>{"code-bad-checksum", "code-tcp-gap"}));
}

TEST(ReportScale, TheVerdictAsTheJsonWritesIt) {
  EXPECT_EQ(to_string(report::ScaleVerdict::field), "0.5");
  EXPECT_EQ(to_string(report::ScaleVerdict::document), "0.1");
  EXPECT_EQ(to_string(report::ScaleVerdict::neither), "neither");
  EXPECT_EQ(to_string(report::ScaleVerdict::none), "");
}

// The time of day from the time itself: it was cut out of format_time's
// text at a fixed place, which a year of five digits (a pcapng timestamp
// can reach it) shifts: "T12:00:00.12".
TEST(ReportClock, TimeOfDayFromTheTime) {
  EXPECT_EQ(report::clock_text(kNoTime), "-");
  EXPECT_EQ(report::clock_text(kT0 + 123'456), "12:00:00.123");
  EXPECT_EQ(report::clock_text(kT0 + 86'399'999'999), "11:59:59.999");
  EXPECT_EQ(report::clock_text(-1), "23:59:59.999");
  constexpr std::int64_t kYear10000 = 253402300800LL * 1'000'000;  // 10000-01-01T00:00:00Z
  EXPECT_EQ(report::clock_text(kYear10000 + 12 * 3'600'000'000LL + 123'456), "12:00:00.123");
}

}  // namespace
}  // namespace topdump
