// topconf drive proved on known bugs (issue 50 item 5): the built topconf
// drive against the built topkit_drive_client, clean or with one --bug, each
// run its JSON report checked: the clean client fails no case and acts on
// every intent its driver has a call for (no case `unimplemented`), each
// bug fails exactly the cases its bug_table row gives it, no case is an `error`. One
// test per run (ctest spreads them); every case of a run at once (--jobs),
// the short durations: a run takes its longest case, about 4.5 s, and a
// fraction of a second of CPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "binaries.hpp"
#include "drive_client/drive_api.hpp"

namespace {

namespace fs = std::filesystem;

// The case IDs of docs/DRIVE.md (stable).
const std::vector<std::string> kCases = {"1.1", "1.2", "1.3", "1.4", "2.1", "2.2", "2.3",
                                         "2.4", "2.5", "3.1", "3.2", "3.3", "3.4", "4.1",
                                         "5.1", "6.1", "6.2", "6.3", "6.4", "6.5", "7.1",
                                         "7.2", "7.3", "8.1", "8.2", "8.3", "9.1"};

// The cases each bug fails: the client's own table (drive_api.hpp
// bug_table, which --help prints and docs/DRIVE.md "Known driver bugs"
// gives with the reasons where a bug fails more than the case that names
// it).
std::set<std::string> fails_of(const std::string& bug) {
  std::set<std::string> out;
  for (const drive::BugInfo& b : drive::bug_table())
    if (b.name == bug) {
      std::string c(b.cases);
      for (std::size_t i = 0; i < c.size();) {
        const std::size_t sp = std::min(c.find(' ', i), c.size());
        out.insert(c.substr(i, sp - i));
        i = sp + 1;
      }
    }
  return out;
}

struct ProofRun {
  std::string model, link, bug;
  std::vector<std::string> only;  // the cases run (empty: all)
};

std::string name_of(const ProofRun& r) {
  std::string s = r.model + "_" + r.link + "_" + (r.bug.empty() ? "clean" : r.bug);
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

std::vector<ProofRun> runs() {
  std::vector<ProofRun> v;
  v.push_back({"sip", "pty", "", {}});
  // On a pty U is the right address: the address bug has nothing to fail.
  for (const drive::BugInfo& b : drive::bug_table())
    if (b.topotek && b.bug != drive::Bug::uart_address_on_network)
      v.push_back({"sip", "pty", std::string(b.name), {}});
  v.push_back({"sip", "udp", "", {}});
  // On a network link a Topotek camera answers no request of source U: the
  // bug loses every answer; 6.4 is the case that judges the address.
  v.push_back({"sip", "udp", "uart-address-on-network", {"6.4"}});
  for (const char* m : {"c12", "c13"}) v.push_back({m, "udp", "", {}});
  for (const drive::BugInfo& b : drive::bug_table())
    if (b.skydroid) v.push_back({"c12", "udp", std::string(b.name), {}});
  return v;
}

void PrintTo(const ProofRun& r, std::ostream* os) { *os << name_of(r); }

class DriveProof : public ::testing::TestWithParam<ProofRun> {};

TEST_P(DriveProof, EachBugFailsExactlyItsCases) {
  const ProofRun& r = GetParam();
  const fs::path out = fs::path(TOPKIT_BINARY_DIR) / "drive-proof" / name_of(r);
  fs::remove_all(out);
  fs::create_directories(out);
  const std::string client =
      std::string(TOPKIT_BINARY_DIR) + "/tests/conformance/topkit_drive_client";
  std::string exec = "'" + client + "' --driver " +
                     (r.model == "sip" ? "ardupilot-topotek" : "ardupilot-skydroid") +
                     (r.link == "pty" ? " --pty {pty}" : " --udp {host}:{port}");
  if (!r.bug.empty()) exec += " --bug " + r.bug;
  const std::string report = (out / "report.json").string();
  std::string cmd = "'" + bin("topconf") + "' drive --model " + r.model + " --link " + r.link +
                    " --jobs 32 -q --no-color --out '" + (out / "run").string() + "' --json '" +
                    report + "' --exec \"" + exec + "\"";
  const std::vector<std::string>& cases = r.only;
  for (const std::string& c : cases) cmd += " --case " + c;
  const int rc = run_cmd(cmd);
  SCOPED_TRACE(cmd);

  std::ifstream in(report);
  const auto j = nlohmann::json::parse(in, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << "no JSON report; topconf exit " << rc;
  std::set<std::string> failed, want;
  if (!r.bug.empty()) want = fails_of(r.bug);
  std::string grades;
  for (const auto& c : j.value("cases", nlohmann::json::array())) {
    const std::string id = c.value("id", ""), grade = c.value("grade", "");
    grades += id + " " + grade + ": " + c.value("reason", "") + "\n";
    EXPECT_NE(grade, "error") << id << ": " << c.value("reason", "");
    if (r.bug.empty()) {
      EXPECT_NE(grade, "unimplemented") << id << ": " << c.value("reason", "");
    }
    if (grade == "fail") failed.insert(id);
  }
  EXPECT_EQ(failed, want) << grades;
  EXPECT_EQ(rc, want.empty() ? 0 : 1) << grades;
  EXPECT_EQ(j.value("exit_code", -1), rc);
  const std::size_t ran = cases.empty() ? kCases.size() : cases.size();
  EXPECT_EQ(j.value("cases", nlohmann::json::array()).size(), ran);
}

INSTANTIATE_TEST_SUITE_P(Runs, DriveProof, ::testing::ValuesIn(runs()),
                         [](const auto& i) { return name_of(i.param); });

}  // namespace
