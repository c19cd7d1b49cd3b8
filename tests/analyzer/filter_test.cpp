// The command line's selection applies to everything reported alike:
// frames, findings, statistics and the exit status (issue #7 items 6-7).
// These run the built topdump on the bundled captures.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "test_support.hpp"

namespace topdump::test {
namespace {

std::string td() { return "'" + topdump_bin() + "' "; }
std::string cap_arg(const std::string& name) { return " '" + captures_dir() + "/" + name + "'"; }

// The JSON Lines of `topdump read --json ARGS`, one object per line.
std::vector<nlohmann::json> lines(const std::string& args, int& rc) {
  std::string out;
  rc = run(td() + "read --json " + args + " 2>/dev/null", out);
  std::vector<nlohmann::json> v;
  std::istringstream in(out);
  for (std::string l; std::getline(in, l);) {
    auto j = nlohmann::json::parse(l);
    if (j["type"] != "input") v.push_back(std::move(j));  // what the input was read as
  }
  return v;
}

TEST(Filter, IdentSelectsFindingsAndExitStatusToo) {
  // sample.pcap's GAA exchange is clean; the unanswered GAY/VER/PTZ
  // requests are not about GAA and must not show or fail the run.
  int rc = -1;
  auto v = lines("--ident GAA" + cap_arg("sample.pcap"), rc);
  ASSERT_EQ(v.size(), 2u);
  for (const auto& j : v) {
    EXPECT_EQ(j["type"], "frame");
    EXPECT_EQ(j["ident"], "GAA");
  }
  EXPECT_EQ(rc, 0);
  lines("" + cap_arg("sample.pcap"), rc);
  EXPECT_EQ(rc, 1);  // unfiltered, the capture has an error
  // The same in lower case.
  auto w = lines("--ident gaa" + cap_arg("sample.pcap"), rc);
  EXPECT_EQ(w.size(), 2u);
  EXPECT_EQ(rc, 0);
}

TEST(Filter, AddressThatMatchesNothingReportsNothing) {
  std::string out;
  EXPECT_EQ(run(td() + "read --addr 10.9.9.9" + cap_arg("sample.pcap") + " 2>/dev/null", out), 0);
  EXPECT_EQ(out, "");
}

TEST(Filter, UnansweredRequestsFollowTheIdent) {
  int rc = -1;
  auto v = lines("--ident VER" + cap_arg("sample.pcap"), rc);
  int unanswered = 0;
  for (const auto& j : v) {
    if (j["type"] == "frame") {
      EXPECT_EQ(j["ident"], "VER");
    }
    if (j["type"] == "note" || j["type"] == "finding") {
      const std::string text = j.dump();
      EXPECT_NE(text.find("VER"), std::string::npos) << text;
      ++unanswered;
    }
  }
  EXPECT_EQ(unanswered, 1);
  EXPECT_EQ(rc, 0);  // an unanswered request is a warning; the error frames are not VER
}

TEST(Filter, StatsCountOnlyWhatIsSelected) {
  std::string out;
  ASSERT_EQ(run(td() + "stats --json --ident GAA" + cap_arg("sample.pcap") + " 2>/dev/null", out),
            0);
  auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["frames"], 2);
  EXPECT_EQ(j["per_ident"].size(), 1u);
  EXPECT_EQ(j["per_ident"]["GAA"], 2);
  ASSERT_EQ(j["latency"].size(), 1u);
  EXPECT_EQ(j["latency"]["GAA"]["count"], 1);
  EXPECT_EQ(j["pairing"]["requests"], 1);
  EXPECT_EQ(j["pairing"]["responses"], 1);
  EXPECT_EQ(j["pairing"]["paired"], 1);
  EXPECT_EQ(j["pairing"]["unanswered"], 0);
  EXPECT_TRUE(j["per_finding"].empty()) << j["per_finding"].dump();
  ASSERT_EQ(j["conversations"].size(), 1u);
  EXPECT_EQ(j["conversations"][0]["frames"], 2);
  EXPECT_NE(j["worst"], "error");
}

TEST(Filter, FindingSelectsFramesCarryingIt) {
  int rc = -1;
  auto v = lines("--finding tp-length" + cap_arg("sample.pcap"), rc);
  ASSERT_FALSE(v.empty());
  for (const auto& j : v) {
    ASSERT_EQ(j["type"], "frame");
    EXPECT_NE(j.dump().find("tp-length"), std::string::npos) << j.dump();
  }
  // An analyzer code selects the events that carry it.
  auto u = lines("--finding unanswered" + cap_arg("sample.pcap"), rc);
  ASSERT_FALSE(u.empty());
  for (const auto& j : u) EXPECT_NE(j.dump().find("unanswered"), std::string::npos) << j.dump();
  EXPECT_EQ(rc, 0);
  // The bad checksum is an error: selected, it decides the exit status.
  auto b = lines("--finding bad-checksum" + cap_arg("sample.pcap"), rc);
  ASSERT_FALSE(b.empty());
  EXPECT_EQ(rc, 1);
}

TEST(Filter, MuteDropsAFindingEverywhere) {
  std::string all, muted;
  run(td() + "read --json" + cap_arg("sample.pcap") + " 2>/dev/null", all);
  ASSERT_NE(all.find("tp-length"), std::string::npos);
  run(td() + "read --json --mute tp-length" + cap_arg("sample.pcap") + " 2>/dev/null", muted);
  EXPECT_EQ(muted.find("tp-length"), std::string::npos);
  // Every frame is still there.
  EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), std::count(muted.begin(), muted.end(), '\n'));
  std::string out;
  run(td() + "stats --json --mute tp-length,unanswered" + cap_arg("sample.pcap") + " 2>/dev/null",
      out);
  auto j = nlohmann::json::parse(out);
  EXPECT_FALSE(j["per_finding"].contains("tp-length"));
  EXPECT_FALSE(j["per_finding"].contains("unanswered"));
  EXPECT_EQ(j["pairing"]["unanswered"], 0);
}

TEST(Filter, UnknownCodeIsAUsageError) {
  std::string out;
  EXPECT_EQ(run(td() + "read --finding bogus-code" + cap_arg("sample.pcap") + " 2>&1", out), 2);
  EXPECT_NE(out.find("bogus-code"), std::string::npos);
  EXPECT_EQ(run(td() + "read --mute bogus-code" + cap_arg("sample.pcap") + " 2>&1", out), 2);
  EXPECT_EQ(run(td() + "read --from +soon" + cap_arg("sample.pcap") + " 2>&1", out), 2);
}

TEST(Filter, RelativeTimesCountFromTheFirstTimestamp) {
  // sample.pcap starts at 12:00:00.000; +1s is the absolute 12:00:01Z.
  std::string rel, abs;
  run(td() + "read --csv n --from +1s" + cap_arg("sample.pcap") + " 2>/dev/null", rel);
  run(td() + "read --csv n --from 2024-05-01T12:00:01Z" + cap_arg("sample.pcap") + " 2>/dev/null",
      abs);
  EXPECT_EQ(rel, abs);
  EXPECT_NE(rel, "n\n");
  std::string ms;
  run(td() + "read --csv n --from +300ms --to +305ms" + cap_arg("sample.pcap") + " 2>/dev/null",
      ms);
  std::string abs2;
  run(td() + "read --csv n --from 1714564800.3 --to 1714564800.305" + cap_arg("sample.pcap") +
          " 2>/dev/null",
      abs2);
  EXPECT_EQ(ms, abs2);
}

TEST(Filter, CountStopsAfterNSelectedFrames) {
  int rc = -1;
  auto v = lines("-c 3" + cap_arg("sample.pcap"), rc);
  ASSERT_EQ(v.size(), 3u);
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_EQ(v[i]["type"], "frame");
    EXPECT_EQ(v[i]["n"], static_cast<int>(i + 1));
  }
  // The input was cut short: nothing pending is called unanswered.
  EXPECT_EQ(rc, 0);
  auto g = lines("-c 2 --ident GAY" + cap_arg("sample.pcap"), rc);
  ASSERT_EQ(g.size(), 2u);
  for (const auto& j : g) EXPECT_EQ(j["ident"], "GAY");
}

TEST(Filter, CountStopsReadingTheCapture) {
  TempDir tmp;
  const std::string capture = generated_capture(tmp, "c.pcap", 5000, 3);
  ASSERT_FALSE(capture.empty());
  std::string out;
  run(td() + "stats --json -c 10 '" + capture + "' 2>/dev/null", out);
  auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["frames"], 10);
  EXPECT_LT(j["records"].get<int>(), 100);  // not the 5,000 records of the file
}

TEST(Filter, Ipv6HostWithoutBrackets) {
  std::string bare, bracketed;
  run(td() + "read --csv n --addr fd00::10" + cap_arg("ipv6.pcap") + " 2>/dev/null", bare);
  run(td() + "read --csv n --addr [fd00::10]" + cap_arg("ipv6.pcap") + " 2>/dev/null", bracketed);
  EXPECT_NE(bare, "n\n");
  EXPECT_EQ(bare, bracketed);
}

}  // namespace
}  // namespace topdump::test
