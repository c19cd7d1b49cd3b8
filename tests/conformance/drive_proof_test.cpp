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

// One `topconf drive` run and what its JSON report says.
struct Outcome {
  std::string cmd;
  int rc = -1;
  nlohmann::json report;  // discarded when there is none
  std::set<std::string> failed;
  std::string grades;  // "id grade: reason" lines
};

Outcome drive_once(const ProofRun& r, const fs::path& out) {
  fs::remove_all(out);
  fs::create_directories(out);
  const std::string client =
      std::string(TOPKIT_BINARY_DIR) + "/tests/conformance/topkit_drive_client";
  std::string exec = "'" + client + "' --driver " +
                     (r.model == "sip" ? "ardupilot-topotek" : "ardupilot-skydroid") +
                     (r.link == "pty" ? " --pty {pty}" : " --udp {host}:{port}");
  if (!r.bug.empty()) exec += " --bug " + r.bug;
  const std::string report = (out / "report.json").string();
  Outcome o;
  o.cmd = "'" + bin("topconf") + "' drive --model " + r.model + " --link " + r.link +
          " --jobs 32 -q --no-color --out '" + (out / "run").string() + "' --json '" + report +
          "' --exec \"" + exec + "\"";
  for (const std::string& c : r.only) o.cmd += " --case " + c;
  o.rc = run_cmd(o.cmd);
  std::ifstream in(report);
  o.report = nlohmann::json::parse(in, nullptr, false);
  if (o.report.is_discarded()) return o;
  for (const auto& c : o.report.value("cases", nlohmann::json::array())) {
    const std::string id = c.value("id", ""), grade = c.value("grade", "");
    o.grades += id + " " + grade + ": " + c.value("reason", "") + "\n";
    if (grade == "fail") o.failed.insert(id);
  }
  return o;
}

TEST_P(DriveProof, EachBugFailsExactlyItsCases) {
  const ProofRun& r = GetParam();
  const fs::path out = fs::path(TOPKIT_BINARY_DIR) / "drive-proof" / name_of(r);
  std::set<std::string> want;
  if (!r.bug.empty()) want = fails_of(r.bug);
  Outcome o = drive_once(r, out);
  // Once more when the first run's failures are not the bug's: every case
  // is judged on sub-second timing, and this VM's host has stalled every
  // pty of the machine for 1.3 s at once (CI, f2e675d: the simulators kept
  // their 100 ms stream, no client's bytes arrived, three concurrent runs
  // alike). A bug fails its cases on every run, so it fails the second
  // run too; the first run's grades are printed either way.
  if (o.report.is_discarded() || o.failed != want) {
    std::fprintf(stderr, "drive_proof: %s: first run failed {", name_of(r).c_str());
    for (const std::string& id : o.failed) std::fprintf(stderr, " %s", id.c_str());
    std::fprintf(stderr, " } (exit %d), running it once more:\n%s", o.rc, o.grades.c_str());
    o = drive_once(r, out);
  }
  SCOPED_TRACE(o.cmd);
  ASSERT_FALSE(o.report.is_discarded()) << "no JSON report; topconf exit " << o.rc;
  for (const auto& c : o.report.value("cases", nlohmann::json::array())) {
    const std::string id = c.value("id", ""), grade = c.value("grade", "");
    EXPECT_NE(grade, "error") << id << ": " << c.value("reason", "");
    if (r.bug.empty()) {
      EXPECT_NE(grade, "unimplemented") << id << ": " << c.value("reason", "");
    }
  }
  EXPECT_EQ(o.failed, want) << o.grades;
  EXPECT_EQ(o.rc, want.empty() ? 0 : 1) << o.grades;
  EXPECT_EQ(o.report.value("exit_code", -1), o.rc);
  const std::size_t ran = r.only.empty() ? kCases.size() : r.only.size();
  EXPECT_EQ(o.report.value("cases", nlohmann::json::array()).size(), ran);
}

INSTANTIATE_TEST_SUITE_P(Runs, DriveProof, ::testing::ValuesIn(runs()),
                         [](const auto& i) { return name_of(i.param); });

}  // namespace
