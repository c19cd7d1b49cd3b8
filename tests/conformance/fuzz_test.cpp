// topconf fuzz: the cases (reproducible by index and seed), the runner
// against topsim with each firmware fault (in process, on a virtual clock)
// and against a healthy topsim over UDP loopback, and the CLI end to end.
#include "conf/fuzz.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "binaries.hpp"
#include "conf/fuzz_report.hpp"
#include "running_server.hpp"
#include "sim/faults.hpp"
#include "test_matrix_util.hpp"
#include "top/frame.hpp"
#include "top/text.hpp"

namespace {

using topconf::FailureClass;
using topconf::FuzzOptions;
using topconf::MinimiseHow;

topconf::FuzzResult fuzz_sim(top::Model model, std::string_view faults, std::uint64_t cases,
                             std::uint64_t seed = 1) {
  std::string err;
  auto fc = topsim::parse_faults(faults, err);
  EXPECT_TRUE(fc.has_value()) << err;
  topconf::SimTransport t(model, fc.value_or(topsim::FaultConfig{}), 1);
  FuzzOptions o;
  o.seed = seed;
  o.end = cases;
  o.restart = [&t] { return t.restart(); };
  o.slow_ms = 300;
  return topconf::run_fuzz(default_matrix(model), t, o);
}

TEST(FuzzCases, TheSameSeedGivesTheSameCasesByteForByte) {
  const auto m = default_matrix(top::Model::c12);
  const topconf::CaseSource a(top::Model::c12, 'U', 42, &m), b(top::Model::c12, 'U', 42, &m),
      other(top::Model::c12, 'U', 43, &m);
  ASSERT_GT(a.catalog_cases(), 500u);
  std::size_t differ = 0;
  for (std::uint64_t i = 0; i < 6000; ++i) {
    const auto x = a.at(i), y = b.at(i);
    ASSERT_EQ(x.bytes, y.bytes) << i;
    ASSERT_EQ(x.name, y.name) << i;
    differ += x.bytes != other.at(i).bytes;
  }
  // Generating out of order changes nothing: the case is its index.
  EXPECT_EQ(a.at(5999).bytes, b.at(5999).bytes);
  EXPECT_GT(differ, 1000u);                     // mutations follow the seed
  EXPECT_EQ(a.at(3).bytes, other.at(3).bytes);  // catalog cases do not
}

TEST(FuzzCases, TheCatalogFamiliesAreThere) {
  const auto m = default_matrix(top::Model::sip);
  const topconf::CaseSource s(top::Model::sip, 'P', 1, &m);
  std::map<std::string, std::size_t> families;
  std::size_t silence = 0, answer = 0, error = 0;
  for (std::uint64_t i = 0; i < s.catalog_cases(); ++i) {
    const auto c = s.at(i);
    ++families[c.family];
    silence += c.promise == topconf::Promise::silence;
    answer += c.promise == topconf::Promise::answer;
    error += c.promise == topconf::Promise::error;
  }
  for (const char* f : {"oversized", "binary", "unknown-ident", "address", "control", "framing",
                        "valid", "value", "length", "header", "checksum"})
    EXPECT_GT(families[f], 0u) << f;
  EXPECT_GT(silence, 50u);
  EXPECT_GT(answer, 50u);
  EXPECT_GT(error, 10u);
  const auto mut = s.at(s.catalog_cases() + 7);
  EXPECT_TRUE(mut.mutated);
  EXPECT_EQ(mut.family, "mutation");
}

// The malformed frames the catalog families forge, byte for byte: lengths
// that lie, checksums over another header or in lowercase, wrong and missing
// checksums, odd addresses, control chars and identifiers.
TEST(FuzzCases, TheForgedFramesByteForByte) {
  using namespace std::string_literals;
  struct Forged {
    top::Model model;
    char client;
    std::string name, bytes;
  };
  const Forged forged[] = {
      {top::Model::c12, 'U', "#Tp declares 65535, carries 100",
       "#TpUG\xFF\xFF"s + "GAY" + std::string(100, '1') + "00"},
      {top::Model::c12, 'U', "#tP declares 255, carries 10",
       "#tPUG\xFF"s + "wGAY1111111111" + "00"},
      {top::Model::c12, 'U', "#tp data of 40 chars under a one-digit length",
       "#tpUGFwGAY" + std::string(40, '0') + "C1"},
      {top::Model::c12, 'U', "bad identifier gay", "#TPUD2rgay00A5"},
      {top::Model::c12, 'U', "bad identifier GA\\x01", "#TPUD2rGA\x01"s + "00ED"},
      {top::Model::c12, 'U', "source \\x00", "#TP\0"s + "D2rAWB00E9"},
      {top::Model::c12, 'U', "destination \\x7F", "#TPU\x7F"s + "2rAWB0079"},
      {top::Model::c12, 'U', "control char \\x00", "#TPUD2\0"s + "AWB00CC"},
      {top::Model::c12, 'U', "control char \\x00 in the data", "#TPUD2rAWB\0"s + "00E"},
      {top::Model::c12, 'U', "a frame inside another's data",
       "#tPUG\x0E"s + "wGAY#TPUD2rAWB003E9F"},
      {top::Model::c12, 'U', "PTZ w lowercase checksum", "#TPUG2wPTZ146f"},
      {top::Model::c12, 'U', "PTZ w checksum over the other header case", "#TPUG2wPTZ14AF"},
      {top::Model::c12, 'U', "GAY w wrong checksum", "#TPUG6wGAY00003217"},
      {top::Model::c12, 'U', "GAY w no checksum", "#TPUG6wGAY000032"},
      {top::Model::c12, 'U', "GAY w checksum over the other header case", "#TPUG6wGAY00003256"},
      {top::Model::c12, 'U', "IQE w length char one less", "#tpUDBwIQE038080808080A3"},
      {top::Model::c12, 'U', "IQE w length char one more", "#tpUDDwIQE038080808080A5"},
      {top::Model::c12, 'U', "IQE w lowercase checksum", "#tpUDCwIQE038080808080a4"},
      {top::Model::c12, 'U', "IQE w checksum over the other header case",
       "#tpUDCwIQE03808080808064"},
      {top::Model::sip, 'P', "ZMC w length char one less", "#tpPM1wZMC0298"},
      {top::Model::sip, 'P', "ZMC w length char one more", "#tpPM3wZMC029A"},
      {top::Model::sip, 'P', "ZMC w checksum over the other header case", "#tpPM2wZMC0259"},
      {top::Model::sip, 'P', "ZOM r lowercase checksum", "#tpPM2rZOM009e"},
      {top::Model::sip, 'P', "TMP w lowercase checksum",
       "#tPPD\x16"s + "wTMP0A08000000A080000000004b"},
      // #tP and #Tp sum alike ('t' + 'P' == 'T' + 'p'): the same bytes.
      {top::Model::sip, 'P', "TMP w checksum over the other header case",
       "#tPPD\x16"s + "wTMP0A08000000A080000000004B"},
  };
  for (const Forged& f : forged) {
    const topconf::CaseSource s(f.model, f.client, 1, nullptr);
    // A command with two forms (TMP w) has two cases of the name.
    std::string seen;
    std::size_t found = 0;
    for (std::uint64_t i = 0; i < s.catalog_cases(); ++i) {
      const auto c = s.at(i);
      if (c.name != f.name) continue;
      found += c.bytes == f.bytes;
      seen += " " + top::escape(c.bytes);
    }
    EXPECT_EQ(found, 1u) << f.name << ":" << seen;
  }
}

struct FaultCase {
  const char* faults;
  FailureClass cls;
};

class FuzzFinds : public ::testing::TestWithParam<FaultCase> {};

TEST_P(FuzzFinds, EachFirmwareFaultWithinTheFirst5000Cases) {
  const FaultCase& fc = GetParam();
  const auto r = fuzz_sim(top::Model::c12, fc.faults, 5000);
  EXPECT_EQ(r.exit_code(), 1);
  ASSERT_FALSE(r.failures.empty()) << fc.faults;
  const auto& f = r.failures.front();
  EXPECT_EQ(f.cls, fc.cls) << topconf::failure_line(f);
  EXPECT_LT(f.index, 5000u);
  EXPECT_EQ(f.how, MinimiseHow::alone) << topconf::failure_line(f);
  EXPECT_EQ(f.cases, std::vector<std::uint64_t>{f.index});
  // Minimised to one frame that parses.
  ASSERT_FALSE(f.frame.empty()) << topconf::failure_line(f);
  EXPECT_EQ(top::parse_exact(f.frame).status, top::ParseStatus::frame);
  EXPECT_NE(topconf::failure_line(f).find("case " + std::to_string(f.index)), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    Faults, FuzzFinds,
    ::testing::Values(FaultCase{"crash-on=ident:GAY", FailureClass::stopped},
                      FaultCase{"crash-on=len:255", FailureClass::stopped},
                      FaultCase{"crash-on=byte:FF", FailureClass::stopped},
                      FaultCase{"hang-on=ident:ZMC,hang-s=5", FailureClass::stopped},
                      FaultCase{"slow-on=ident:PTZ,slow-ms=450", FailureClass::slow},
                      FaultCase{"answer-corrupt", FailureClass::accepted_corrupt}),
    [](const ::testing::TestParamInfo<FaultCase>& p) {
      std::string name = p.param.faults;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

TEST(Fuzz, AHealthyDeviceHasNoFailureAndTheReportsSaySo) {
  for (top::Model m : top::all_models()) {
    const auto r = fuzz_sim(m, "", 3000, 7);
    EXPECT_EQ(r.exit_code(), 0) << top::to_string(m);
    for (const auto& f : r.failures)
      ADD_FAILURE() << top::to_string(m) << ": " << topconf::failure_line(f);
  }
}

// A device link on which a datagram the kernel took before anything was
// sent comes first after each of the first sends (the liveness probe's and
// the first cases'): a late ERE, stamped at the link's
// start (over UDP loopback a late answer that sat in the socket's queue is
// read after the next case went out; CI saw "the first answer after the
// case took 18446744073709551 ms", its time before the send).
class LateEreFirst : public topconf::Transport {
 public:
  explicit LateEreFirst(topconf::Transport& t) : t_(t), late_at_(t.now_us() - 1) {}
  std::uint64_t now_us() override { return t_.now_us(); }
  bool datagram() const override { return t_.datagram(); }
  char client_address() const override { return t_.client_address(); }
  void send(std::string_view bytes) override {
    late_ = sends_++ < 4;
    t_.send(bytes);
  }
  bool receive(std::uint64_t deadline_us, std::string& out) override {
    if (late_) {
      late_ = false;
      out = top::with_checksum("#TPGU2wERE!!");
      arrived_ = late_at_;
      return true;
    }
    const bool got = t_.receive(deadline_us, out);
    arrived_ = t_.arrived_us();
    return got;
  }
  std::uint64_t arrived_us() override { return arrived_; }
  std::string describe() const override { return "late ERE, then " + t_.describe(); }

 private:
  topconf::Transport& t_;
  bool late_ = false;
  int sends_ = 0;
  std::uint64_t late_at_ = 0, arrived_ = 0;
};

// topconf fuzz against a healthy topsim c12 over UDP loopback: `cases`
// cases, the probe every 10, through LateEreFirst when `late_ere_first`.
topconf::FuzzResult fuzz_c12_over_udp(std::uint64_t cases, bool late_ere_first) {
  topsim::ServerConfig cfg;
  cfg.model = top::Model::c12;
  RunningServer srv(cfg);
  auto udp = topconf::open_transport("udp://127.0.0.1:" + std::to_string(srv.server.port()),
                                     top::Model::c12);
  std::optional<LateEreFirst> late;
  if (late_ere_first) late.emplace(*udp);
  FuzzOptions o;
  o.end = cases;
  o.probe_every = 10;
  return topconf::run_fuzz(default_matrix(top::Model::c12),
                           late ? static_cast<topconf::Transport&>(*late) : *udp, o);
}

TEST(Fuzz, HealthyTopsimOverUdpLoopback5000Cases) {
  const auto r = fuzz_c12_over_udp(5000, false);
  EXPECT_EQ(r.exit_code(), 0);
  EXPECT_EQ(r.cases_run, 5000u);
  for (const auto& f : r.failures) ADD_FAILURE() << topconf::failure_line(f);
}

TEST(Fuzz, ADatagramFromBeforeTheCaseIsNotItsAnswer) {
  const auto r = fuzz_c12_over_udp(20, true);
  EXPECT_EQ(r.cases_run, 20u);
  EXPECT_EQ(r.exit_code(), 0);
  for (const auto& f : r.failures) ADD_FAILURE() << topconf::failure_line(f);
}

TEST(Fuzz, AnUnusableTargetIsExit2) {
  // Nobody answers there.
  auto t = topconf::open_transport("udp://127.0.0.1:9", top::Model::c12);
  auto m = default_matrix(top::Model::c12);
  m.probe_timeout_ms = 50;
  FuzzOptions o;
  o.end = 10;
  EXPECT_EQ(topconf::run_fuzz(m, *t, o).exit_code(), 2);
}

// ---- the binaries

// The probe waits 500 ms (150 ms once missed a healthy answer on a loaded
// machine); the executable runs alone (tests/conformance/CMakeLists.txt).
// The restart command acts after it returns (SIGHUP 150 ms later, as
// `kill -HUP` under load can): the device restarted to reproduce the
// failure must not be restarted again for the replay, where the late
// restart would land while the replay waits 300 ms (--timeout-ms) for the
// crashed device's ERE, and the crash would "not reproduce" (it did once
// under ASan with a plain `kill -HUP`).
TEST(FuzzCli, FindsACrashOverUdpRestartsWithSighupAndWritesEveryReport) {
  std::string line;
  const pid_t pid = start_topsim(
      {"--model", "c12", "--udp", "127.0.0.1:0", "--fault", "crash-on=ident:GAY"}, line);
  ASSERT_GT(pid, 0);
  ASSERT_EQ(line.rfind("udp 127.0.0.1:", 0), 0u) << line;
  const std::string dir = std::string(TOPKIT_BINARY_DIR) + "/topconf_fuzz_cli";
  run_cmd("mkdir -p " + dir);
  const int rc = run_cmd(bin("topconf") + " fuzz --model c12 --target udp://" + line.substr(4) +
                         " --cases 3000 --max-failures 1 --probe-timeout-ms 500 --slow-ms 200 "
                         "--timeout-ms 300 --restart-cmd '(sleep 0.15; kill -HUP " +
                         std::to_string(pid) + ") &' --json " + dir + "/f.jsonl --junit " + dir +
                         "/f.xml --html " + dir + "/f.html --pcap " + dir + "/f.pcap -q");
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
  EXPECT_EQ(rc, 1);
  std::istringstream in(read_text(dir + "/f.jsonl"));
  std::string l;
  std::size_t cases = 0;
  nlohmann::json failure, summary;
  while (std::getline(in, l)) {
    auto j = nlohmann::json::parse(l);
    if (j.contains("failure") && failure.is_null()) failure = j;
    if (j.contains("summary")) summary = j["summary"];
    if (j.contains("index") && j.contains("verdict")) ++cases;
  }
  EXPECT_GE(cases, 1u);
  ASSERT_FALSE(failure.is_null());
  EXPECT_EQ(failure["failure"], "stopped-answering");
  EXPECT_EQ(failure["minimised"], "alone") << failure.dump();
  EXPECT_NE(failure["frame"].get<std::string>().find("GAY"), std::string::npos);
  EXPECT_TRUE(failure["restarted"].get<bool>());
  EXPECT_EQ(summary["exit"], 1);
  const std::string xml = read_text(dir + "/f.xml");
  EXPECT_NE(xml.find("name=\"stopped-answering\" time=\"0\"><failure"), std::string::npos);
  EXPECT_NE(xml.find("name=\"bad-reply\" time=\"0\"></testcase>"), std::string::npos);
  EXPECT_NE(read_text(dir + "/f.html").find("<h1>topconf fuzz report: c12</h1>"),
            std::string::npos);
  // topdump reads the session's pcap.
  const int td =
      run_cmd(std::string(TOPKIT_BINARY_DIR) + "/analyzer/topdump stats " + dir + "/f.pcap");
  EXPECT_TRUE(td == 0 || td == 1) << td;
}

TEST(FuzzCli, ADeviceKilledMidRunIsReportedWithItsCase) {
  std::string line;
  const pid_t pid = start_topsim({"--model", "c12", "--udp", "127.0.0.1:0"}, line);
  ASSERT_GT(pid, 0);
  const std::string out = std::string(TOPKIT_BINARY_DIR) + "/topconf_fuzz_killed.txt";
  std::thread killer([pid] {
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    kill(pid, SIGKILL);
  });
  const auto t0 = std::chrono::steady_clock::now();
  const int rc =
      std::system((bin("topconf") + " fuzz --model c12 --target udp://" + line.substr(4) +
                   " --cases 1000000 -q --recover-ms 500 > " + out + " 2>&1")
                      .c_str());
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  killer.join();
  waitpid(pid, nullptr, 0);
  EXPECT_EQ(WEXITSTATUS(rc), 1);
  EXPECT_LT(secs, 10.0);
  const std::string text = read_text(out);
  EXPECT_NE(text.find("stopped-answering: the device stopped answering after this case"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("aborted: the device stopped answering at case "), std::string::npos) << text;
}

TEST(FuzzCli, TwoRunsWithTheSameSeedSendTheSameBytesAndResumeGoesOn) {
  const std::string dir = std::string(TOPKIT_BINARY_DIR) + "/topconf_fuzz_seed";
  run_cmd("mkdir -p " + dir);
  auto bytes_of = [](const std::string& path) {
    std::vector<std::string> v;
    std::istringstream in(read_text(path));
    std::string l;
    while (std::getline(in, l)) {
      auto j = nlohmann::json::parse(l);
      if (j.contains("verdict"))
        v.push_back(std::to_string(j["index"].get<std::uint64_t>()) + " " +
                    j["bytes"].get<std::string>());
    }
    return v;
  };
  const std::string base = bin("topconf") + " fuzz --model sip --target sim -q --seed 9 ";
  EXPECT_EQ(run_cmd(base + "--start 2000 --cases 1500 --json " + dir + "/a.jsonl"), 0);
  EXPECT_EQ(run_cmd(base + "--start 2000 --cases 1500 --json " + dir + "/b.jsonl"), 0);
  const auto a = bytes_of(dir + "/a.jsonl");
  ASSERT_EQ(a.size(), 1500u);
  EXPECT_EQ(a, bytes_of(dir + "/b.jsonl"));
  // --case N replays one case exactly.
  EXPECT_EQ(run_cmd(base + "--case 2345 --json " + dir + "/c.jsonl"), 0);
  const auto c = bytes_of(dir + "/c.jsonl");
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0], a[345]);
  // --resume continues after the last case of the file, with its seed.
  EXPECT_EQ(run_cmd(bin("topconf") + " fuzz --model sip --target sim -q --cases 100 --resume " +
                    dir + "/b.jsonl"),
            0);
  const auto b = bytes_of(dir + "/b.jsonl");
  ASSERT_EQ(b.size(), 1600u);
  EXPECT_EQ(b[1500].rfind("3500 ", 0), 0u);
  EXPECT_EQ(run_cmd(base + "--start 3500 --cases 1 --json " + dir + "/d.jsonl"), 0);
  EXPECT_EQ(bytes_of(dir + "/d.jsonl")[0], b[1500]);
  // Bad usage and a bad resume file.
  EXPECT_EQ(run_cmd(bin("topconf") + " fuzz --model sip --target sim --resume /nonexistent"), 2);
  EXPECT_EQ(run_cmd(bin("topconf") + " fuzz --model sip --target bogus://x"), 2);
  EXPECT_EQ(run_cmd(bin("topconf") + " fuzz --model sip --target sim --sim-fault crash-on=x"), 2);
}

}  // namespace

namespace {

TEST(FuzzCli, DurationAndRateBoundTheRun) {
  const std::string out = std::string(TOPKIT_BINARY_DIR) + "/topconf_fuzz_bounds.txt";
  auto timed = [&](const std::string& args) {
    const auto t0 = std::chrono::steady_clock::now();
    const int rc = std::system(
        (bin("topconf") + " fuzz --model c12 --target sim -q " + args + " > " + out).c_str());
    EXPECT_EQ(WEXITSTATUS(rc), 0) << args;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  EXPECT_LT(timed("--cases 100000000 --duration 0.5"), 5.0);
  EXPECT_NE(read_text(out).find("next index"), std::string::npos);
  EXPECT_GE(timed("--cases 60 --rate 200"), 0.25);
  EXPECT_EQ(read_text(out).rfind("60 case(s)", 0), 0u) << read_text(out);
}

}  // namespace
