// topkit_drive_client as built: its command line (usage errors, --bug
// names), the intents file's errors, a run against a topsim process over a
// pty and UDP with intents and beliefs on stdout, SIGTERM, a failed write on
// stdout, and an intents file followed as it grows (--persistent).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "binaries.hpp"
#include "drive_client/intents.hpp"
#include "loopback.hpp"

namespace {

const std::string kClient =
    std::string(TOPKIT_BINARY_DIR) + "/tests/conformance/topkit_drive_client";

struct Shell {
  int status = -1;
  std::string out, err;
};

// Runs `cmd` through the shell; its status, stdout and stderr.
Shell shell(const std::string& cmd) {
  // One file per process (ctest runs each test as a process of its own).
  const std::string err =
      std::string(TOPKIT_BINARY_DIR) + "/drive_client_test." + std::to_string(::getpid()) + ".err";
  Shell r;
  FILE* f = ::popen((cmd + " 2>'" + err + "'").c_str(), "r");
  if (!f) return r;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) r.out.append(buf, n);
  const int st = ::pclose(f);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  std::ifstream e(err);
  r.err.assign(std::istreambuf_iterator<char>(e), {});
  std::remove(err.c_str());
  return r;
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string p = std::string(TOPKIT_BINARY_DIR) + "/" + name;
  std::ofstream(p) << text;
  return p;
}

std::vector<nlohmann::json> json_lines(const std::string& out) {
  std::vector<nlohmann::json> v;
  std::size_t start = 0;
  for (std::size_t end; (end = out.find('\n', start)) != std::string::npos; start = end + 1) {
    auto j = nlohmann::json::parse(out.substr(start, end - start), nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << out.substr(start, end - start);
    if (!j.is_discarded()) v.push_back(std::move(j));
  }
  return v;
}

TEST(DriveClient, UsageErrors) {
  Shell r = shell(kClient + " --driver ardupilot-topotek --pty /dev/null --bug no-such-bug");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--bug no-such-bug: no such bug"), std::string::npos) << r.err;
  r = shell(kClient + " --driver ardupilot-skydroid --udp 127.0.0.1:5000 --bug echo-as-attitude");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("not a bug ardupilot-skydroid can have"), std::string::npos) << r.err;
  r = shell(kClient + " --driver px4 --pty /dev/null");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--driver px4: not one of"), std::string::npos) << r.err;
  r = shell(kClient + " --driver ardupilot-topotek");  // no link
  EXPECT_EQ(r.status, 2);
  r = shell(kClient + " --help");
  EXPECT_EQ(r.status, 0);
  for (const char* bug :
       {"pitch-rate-sign", "uart-address-on-network", "strict-version", "echo-as-attitude",
        "range-fixed-offsets", "month-zero-based", "no-stop-after-last-rate",
        "no-reenable-after-reboot", "rates-on-stale-attitude"}) {
    EXPECT_NE(r.out.find(bug), std::string::npos) << bug;
  }
}

TEST(DriveClient, BadIntentsNameFileAndLine) {
  const std::string p = write_file(
      "drive_bad_intents.jsonl", "{\"t\":0.1,\"do\":\"stop\"}\n\n{\"t\":\"x\",\"do\":\"stop\"}\n");
  const Shell r = shell("TOPCONF_INTENT='" + p + "' " + kClient +
                        " --driver ardupilot-topotek --pty /dev/null");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(p + ":3: \"t\" is not a finite number"), std::string::npos) << r.err;
  std::string why;
  EXPECT_TRUE(drive::parse_intents("{\"t\":1,\"do\":\"zoom\",\"rate\":2}", "f", why).empty());
  EXPECT_EQ(why, "f:1: \"rate\" of zoom is not -1, 0 or 1");
  why.clear();
  EXPECT_TRUE(drive::parse_intents("[1]", "f", why).empty());
  EXPECT_EQ(why, "f:1: not a JSON object");
  why.clear();
  EXPECT_TRUE(
      drive::parse_intents("{\"t\":1,\"do\":\"clock\",\"utc\":\"2026-13-01T00:00:00Z\"}", "f", why)
          .empty());
  EXPECT_EQ(why, "f:1: \"utc\" is not YYYY-MM-DDTHH:MM:SSZ");
  // Unknown actions are ignored; the rest sorted by time.
  why.clear();
  const auto v = drive::parse_intents(
      "{\"t\":2,\"do\":\"stop\"}\n{\"t\":1,\"do\":\"case\",\"id\":\"2.1\"}\n{\"t\":1,\"do\":"
      "\"dance\"}\n"
      "{\"t\":0.5,\"do\":\"rate\",\"pitch_dps\":10}\n",
      "f", why);
  EXPECT_TRUE(why.empty()) << why;
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0].what, drive::Intent::Do::rate);
  EXPECT_EQ(v[0].pitch, 10);
  EXPECT_EQ(v[1].what, drive::Intent::Do::case_start);
  EXPECT_EQ(v[2].what, drive::Intent::Do::other);
  EXPECT_EQ(v[3].line, 1u);
}

// Against topsim over a pty and UDP: the pitch rate intent moves the
// device up, the beliefs say so, identity parsed, and SIGTERM ends it with 0.
TEST(DriveClient, DrivesTopsimAndPrintsBeliefs) {
  const std::string intents =
      write_file("drive_intents.jsonl",
                 "{\"t\":0.2,\"do\":\"identity\"}\n{\"t\":0.4,\"do\":\"rate\",\"pitch_dps\":10}\n"
                 "{\"t\":1.4,\"do\":\"stop\"}\n");
  for (const bool pty : {true, false}) {
    SCOPED_TRACE(pty ? "pty" : "udp");
    const std::string host = own_loopback();
    std::vector<std::string> args = {"--model", "sip"};
    if (pty)
      args.emplace_back("--pty");
    else
      args.insert(args.end(), {"--udp", host + ":0"});
    std::string line;
    const pid_t sim = start_topsim(args, line);
    ASSERT_GT(sim, 0);
    const std::string link = pty ? "--pty " + line : "--udp " + line.substr(line.find(' ') + 1);
    // Stopped by SIGTERM after 2 s (timeout's), its status ours.
    const Shell r = shell("TOPCONF_INTENT='" + intents + "' timeout --preserve-status -s TERM 2 " +
                          kClient + " --driver ardupilot-topotek " + link + " --belief-ms 100");
    kill(sim, SIGTERM);
    waitpid(sim, nullptr, 0);
    EXPECT_EQ(r.status, 0) << r.err;
    const auto lines = json_lines(r.out);
    ASSERT_GE(lines.size(), 10u) << r.out;
    const nlohmann::json& last = lines.back();
    EXPECT_TRUE(last.value("healthy", false)) << last;
    EXPECT_EQ(last.value("version", ""), "1.6.26") << last;
    EXPECT_EQ(last.value("model", ""), "SIP") << last;
    ASSERT_TRUE(last.contains("attitude")) << last;
    EXPECT_GT(last["attitude"].value("pitch", 0.0), 6.0) << last;
    EXPECT_FALSE(lines.front().value("healthy", true));
  }
}

// TOPCONF_T0_US (CLOCK_MONOTONIC us of the case's time 0) is the start the
// intents and --duration count from: 5 s ago, a 5.6 s run ends at once; a
// value that is no number is ignored.
TEST(DriveClient, TimeZeroFromTheEnvironment) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(
                      std::chrono::steady_clock::now().time_since_epoch())
                      .count();
  const std::string client = kClient + " --driver ardupilot-topotek --udp 127.0.0.1:9";
  auto timed = [&](const std::string& env, const char* duration) {
    const auto t = std::chrono::steady_clock::now();
    const Shell r = shell(env + " " + client + " --duration " + duration);
    EXPECT_EQ(r.status, 0) << r.err;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  EXPECT_LT(timed("TOPCONF_T0_US=" + std::to_string(us - 5000000), "5.6"), 3.0);
  EXPECT_GT(timed("TOPCONF_T0_US=x5", "0.4"), 0.35);
}

// A failed write on stdout is exit 2 with a message, not a silent run.
TEST(DriveClient, FailedWriteIsAnError) {
  // No device needed: the first beliefs line goes out at the start.
  const Shell r = shell("timeout 5 " + kClient +
                        " --driver ardupilot-skydroid --udp 127.0.0.1:9 --duration 1 > /dev/full");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("write error on standard output"), std::string::npos) << r.err;
}

// --persistent: the intents file grows while the client runs; an intent
// appended after the start is acted on at its time.
TEST(DriveClient, FollowsAGrowingIntentsFile) {
  const std::string p =
      write_file("drive_follow.jsonl", "{\"t\":0.1,\"do\":\"case\",\"id\":\"2.1\"}\n");
  drive::IntentFile f(p);
  std::vector<drive::Intent> got;
  std::string why;
  ASSERT_TRUE(f.poll(got, why)) << why;
  ASSERT_EQ(got.size(), 1u);
  {
    std::ofstream a(p, std::ios::app);
    a << "{\"t\":0.5,\"do\":\"rate\",\"pitch_dps\":10}\n{\"t\":1.2,";  // half a line
  }
  got.clear();
  ASSERT_TRUE(f.poll(got, why)) << why;
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].line, 2u);
  {
    std::ofstream a(p, std::ios::app);
    a << "\"do\":\"nope\"}\n{\"t\":x}\n";
  }
  got.clear();
  EXPECT_FALSE(f.poll(got, why));
  EXPECT_EQ(why, p + ":4: not JSON");

  // The executable: the rate intent appended 0.6 s after the start moves the C12 up.
  const std::string q = write_file("drive_follow2.jsonl", "");
  std::string line;
  const pid_t sim = start_topsim({"--model", "c12", "--pty"}, line);
  ASSERT_GT(sim, 0);
  const std::string out = std::string(TOPKIT_BINARY_DIR) + "/drive_follow.out";
  const pid_t c = fork();
  if (c == 0) {
    const int fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    setenv("TOPCONF_CASE", "persistent", 1);
    setenv("TOPCONF_INTENT", q.c_str(), 1);
    execl(kClient.c_str(), kClient.c_str(), "--driver", "ardupilot-skydroid", "--pty", line.c_str(),
          "--duration", "2", static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  std::ofstream(q, std::ios::app) << "{\"t\":0.8,\"do\":\"rate\",\"pitch_dps\":10}\n";
  int st = 0;
  waitpid(c, &st, 0);
  kill(sim, SIGTERM);
  waitpid(sim, nullptr, 0);
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  std::ifstream in(out);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  const auto lines = json_lines(text);
  ASSERT_FALSE(lines.empty());
  ASSERT_TRUE(lines.back().contains("attitude")) << text;
  EXPECT_GT(lines.back()["attitude"].value("pitch", 0.0), 5.0) << text;
}

}  // namespace
