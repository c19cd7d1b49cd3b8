// topsim and topconf over real transports on loopback: UDP and TCP on
// ephemeral 127.0.0.1 ports, a real pseudo-terminal, pcap recordings read
// back with libpcap, and the two binaries end to end.
#include <gtest/gtest.h>
#include <pcap/pcap.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <utility>

#include "binaries.hpp"
#include "conf/report.hpp"
#include "conf/runner.hpp"
#include "loopback.hpp"
#include "running_server.hpp"
#include "sim/server.hpp"
#include "test_matrix_util.hpp"

namespace {

using topconf::Verdict;

// topsim as the command line serves it (the model's port; UDP: a real
// Topotek camera's routes in the field), on a loopback host of the run's
// own (loopback.hpp), against topconf's transport of the target.
topconf::RunResult run_over(top::Model m, topsim::TransportKind kind,
                            const std::string& record = {},
                            top::Profile profile = top::Profile::field) {
  topsim::ServerConfig cfg;
  cfg.model = m;
  cfg.device_options.profile = profile;
  cfg.kind = kind;
  cfg.record = record;
  cfg.host = own_loopback();
  cfg.port = topsim::default_port(m);
  RunningServer s(cfg);
  std::string target;
  switch (kind) {
    case topsim::TransportKind::udp:
      target = "udp://" + cfg.host + ":" + std::to_string(s.server.port());
      break;
    case topsim::TransportKind::tcp:
      target = "tcp://" + cfg.host + ":" + std::to_string(s.server.port());
      break;
    default:
      target = "serial:" + s.server.pty_path();
      break;
  }
  // bound as `topconf run` binds (open_target: sip on UDP 9004 of its host)
  auto t = topconf::open_target(false, target, m, "", 1, -1);
  topconf::RunOptions o;
  o.settle_ms = 3;  // loopback: duplicates would arrive within a millisecond
  return topconf::run_matrix(default_matrix(m), *t, o);
}

struct Param {
  top::Model model;
  topsim::TransportKind kind;
};

class OverTransport : public ::testing::TestWithParam<Param> {};

TEST_P(OverTransport, DefaultMatrixPasses) {
  auto r = run_over(GetParam().model, GetParam().kind);
  ASSERT_FALSE(r.unreachable) << r.unreachable_reason;
  for (const auto& c : r.cases)
    EXPECT_TRUE(
        (c.verdict == Verdict::pass || (c.verdict == Verdict::non_strict && c.field_form)) &&
        !c.flaky)
        << c.spec->id << ": " << to_string(c.verdict) << " " << c.reason;
  EXPECT_EQ(r.exit_code(), 0);
}

std::vector<Param> params() {
  std::vector<Param> p;
  for (auto m : top::all_models())
    for (auto k :
         {topsim::TransportKind::udp, topsim::TransportKind::tcp, topsim::TransportKind::pty})
      p.push_back({m, k});
  return p;
}

INSTANTIATE_TEST_SUITE_P(All, OverTransport, ::testing::ValuesIn(params()), [](const auto& i) {
  const char* k = i.param.kind == topsim::TransportKind::udp   ? "udp"
                  : i.param.kind == topsim::TransportKind::tcp ? "tcp"
                                                               : "pty";
  return std::string(top::to_string(i.param.model)) + "_" + k;
});

// Reads a pcap back: frames per UDP/TCP payload.
std::vector<std::string> payloads(const std::string& path, int& linktype) {
  char err[PCAP_ERRBUF_SIZE];
  pcap_t* p = pcap_open_offline(path.c_str(), err);
  EXPECT_NE(p, nullptr) << err;
  std::vector<std::string> out;
  if (!p) return out;
  linktype = pcap_datalink(p);
  pcap_pkthdr* h = nullptr;
  const u_char* data = nullptr;
  while (pcap_next_ex(p, &h, &data) == 1) {
    const std::size_t ihl = (data[14] & 0x0F) * 4u;
    const bool tcp = data[14 + 9] == 6;
    const std::size_t l4 = tcp ? ((data[14 + ihl + 12] >> 4) * 4u) : 8u;
    const std::size_t off = 14 + ihl + l4;
    out.emplace_back(reinterpret_cast<const char*>(data) + off, h->caplen - off);
  }
  pcap_close(p);
  return out;
}

// topsim serves the ports of top::known_ports(): the C10 also UDP 9002
// (was a special case in topsim_main), the C12 also UDP 12580 (field: some
// C12 clients send every frame to 5000 and 12580), the C20 TCP 5000.
TEST(Ports, TopsimServesTheLibrarysPorts) {
  EXPECT_EQ(topsim::extra_udp_ports(top::Model::c10), std::vector<std::uint16_t>{9002});
  EXPECT_EQ(topsim::extra_udp_ports(top::Model::c12), std::vector<std::uint16_t>{12580});
  EXPECT_TRUE(topsim::extra_udp_ports(top::Model::sip).empty());
  EXPECT_EQ(topsim::default_port(top::Model::c12), 5000);
  EXPECT_EQ(topsim::default_port(top::Model::sip), 9003);
  EXPECT_EQ(topsim::default_transport(top::Model::c20), topsim::TransportKind::tcp);
  EXPECT_EQ(topsim::default_transport(top::Model::c10), topsim::TransportKind::udp);
}

TEST(Record, TopsimRecordsWhatItReceivesAndSends) {
  const std::string path = std::string(TOPKIT_BINARY_DIR) + "/topsim_record_test.pcap";
  auto r = run_over(top::Model::c12, topsim::TransportKind::udp, path);
  EXPECT_EQ(r.exit_code(), 0);
  int lt = 0;
  auto pl = payloads(path, lt);
  EXPECT_EQ(lt, DLT_EN10MB);
  ASSERT_GT(pl.size(), 100u);
  std::size_t frames = 0;
  for (const auto& p : pl) frames += top::parse_exact(p).status == top::ParseStatus::frame ? 1 : 0;
  EXPECT_GT(frames, pl.size() / 2);
  std::remove(path.c_str());
}

TEST(Record, TopconfWritesThePcapOfTheRun) {
  const std::string path = std::string(TOPKIT_BINARY_DIR) + "/topconf_record_test.pcap";
  {
    pcapio::Recorder w(path, true);
    topconf::SimTransport t(top::Model::c12);
    topconf::RunOptions o;
    o.pcap = &w;
    o.cases = {"skydroid/3.3.1/GAY/write"};
    topconf::run_matrix(default_matrix(top::Model::c12), t, o);
  }
  int lt = 0;
  auto pl = payloads(path, lt);
  ASSERT_GE(pl.size(), 2u);
  bool request = false, echo = false;
  for (const auto& p : pl) {
    auto f = top::parse_exact(p);
    if (f.status != top::ParseStatus::frame || f.frame.ident_view() != "GAY") continue;
    request = request || f.frame.src == 'U';
    echo = echo || f.frame.src == 'G';
  }
  EXPECT_TRUE(request);
  EXPECT_TRUE(echo);
  std::remove(path.c_str());
}

// Field fidelity over real UDP: the default matrix passes under both
// profiles, and topdump reads topsim's recording of the run without a false
// alarm: every unanswered request says why (the matrix sends bad checksums
// and Topotek U requests on purpose), no stream runs off its rate.
TEST(Record, EveryProfileOverUdpPassesAndTopdumpReadsItsRecording) {
  for (top::Profile p : {top::Profile::field, top::Profile::document}) {
    for (top::Model m : top::all_models()) {
      if (m == top::Model::c20) continue;  // TCP only (SkyDroid 2.1); covered above
      const std::string path = std::string(TOPKIT_BINARY_DIR) + "/profile_record_" +
                               std::string(top::to_string(m)) + "_" +
                               std::string(top::to_string(p)) + ".pcap";
      auto r = run_over(m, topsim::TransportKind::udp, path, p);
      EXPECT_EQ(r.exit_code(), 0) << top::to_string(m) << " " << top::to_string(p);
      FILE* f = ::popen(("'" + std::string(TOPKIT_BINARY_DIR) + "/analyzer/topdump' read --json '" +
                         path + "' 2>/dev/null")
                            .c_str(),
                        "r");
      ASSERT_NE(f, nullptr);
      std::string out;
      char buf[65536];
      std::size_t n;
      while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
      ::pclose(f);
      std::size_t lines = 0, start = 0;
      while (start < out.size()) {
        const std::size_t end = out.find('\n', start);
        const auto j = nlohmann::json::parse(out.substr(start, end - start));
        start = end == std::string::npos ? out.size() : end + 1;
        ++lines;
        if (j["type"] != "finding") continue;
        const std::string code = j.value("code", ""), msg = j.value("message", "");
        EXPECT_NE(code, "stream-rate") << top::to_string(m) << " " << top::to_string(p) << msg;
        if (code == "unanswered") {
          EXPECT_TRUE(msg.find("checksum") != std::string::npos ||
                      msg.find("UART") != std::string::npos ||
                      msg.find("not supported") != std::string::npos ||
                      msg.find("is invalid") != std::string::npos)
              << top::to_string(m) << " " << top::to_string(p) << ": " << msg;
        }
      }
      EXPECT_GT(lines, 100u) << path;
      std::remove(path.c_str());
    }
  }
}

// SkyDroid 2.1 gives the C20 TCP 5000 only: topsim serves it over TCP when
// no transport is chosen (it used to pick UDP for every model).
TEST(Server, DefaultTransportIsTcpForTheC20Only) {
  for (top::Model m : top::all_models())
    EXPECT_EQ(topsim::default_transport(m),
              m == top::Model::c20 ? topsim::TransportKind::tcp : topsim::TransportKind::udp)
        << top::to_string(m);
}

TEST(Server, ServesExtraUdpPortsLikeTheC10) {
  topsim::ServerConfig cfg;
  cfg.model = top::Model::c10;
  cfg.extra_udp_ports = {0};  // the CLI puts 9002 here for the C10
  RunningServer s(cfg);
  const auto ports = s.server.udp_ports();
  ASSERT_EQ(ports.size(), 2u);
  for (auto p : ports) {
    auto t = topconf::open_transport("udp://127.0.0.1:" + std::to_string(p), top::Model::c10, 0);
    t->send("#TPUD2rAWB003E");
    std::string got;
    ASSERT_TRUE(t->receive(t->now_us() + 2000000, got)) << p;
    EXPECT_EQ(got.substr(0, 10), "#TPDU2rAWB");
  }
}

// A frame that fails its checksum makes the stream decoder wait for
// look-ahead; on a quiet line the device must still answer the next
// command at once rather than when more bytes arrive.
TEST(Server, AnswersAfterABadFrameOnAQuietLine) {
  topsim::ServerConfig cfg;
  cfg.model = top::Model::c12;
  cfg.kind = topsim::TransportKind::pty;
  RunningServer s(cfg);
  auto t = topconf::open_transport("serial:" + s.server.pty_path(), top::Model::c12, 0);
  t->send("#tpUM0wZMC3B");  // checksum 3B, the sum is 3A
  std::string got;
  EXPECT_FALSE(t->receive(t->now_us() + 60000, got)) << got;
  t->send("#TPUD2rAWB003E");
  std::string all;
  const std::uint64_t deadline = t->now_us() + 300000;
  while (all.find("AWB") == std::string::npos && t->receive(deadline, got)) all += got;
  EXPECT_NE(all.find("#TPDU2rAWB"), std::string::npos) << all;
}

// topsim --serial on a real tty: the slave of a pseudo-terminal we own,
// driven from its master side.
TEST(Server, ServesASerialDevice) {
  int master = -1, slave = -1;
  char name[256] = {0};
  ASSERT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0);
  topsim::ServerConfig cfg;
  cfg.model = top::Model::sip;
  cfg.kind = topsim::TransportKind::serial;
  cfg.device = name;
  {
    RunningServer s(cfg);
    termios t{};
    tcgetattr(master, &t);
    cfmakeraw(&t);
    tcsetattr(master, TCSANOW, &t);
    const std::string req = "#TPUG2rGIC003A";  // UART: source U is answered
    ASSERT_EQ(write(master, req.data(), req.size()), static_cast<ssize_t>(req.size()));
    std::string all;
    for (int i = 0; i < 20 && all.find("GIA") == std::string::npos; ++i) {
      pollfd p{master, POLLIN, 0};
      if (poll(&p, 1, 100) <= 0) continue;
      char buf[256];
      const ssize_t n = read(master, buf, sizeof buf);
      if (n > 0) all.append(buf, static_cast<std::size_t>(n));
    }
    // The field profile answers the GIC query as a real SIP does: a 12-char GIA.
    EXPECT_EQ(all.rfind("#tpGUCrGIA", 0), 0u) << all;
  }
  close(slave);
  close(master);
}

// ---- a device like ArduPilot's simulators (docs/sources/ardupilot.md sections
// 3, 4): replies and pushes keep the request's address order, and VER and AWB
// go unanswered (they answer neither). topconf's probe falls back to what
// the catalog says the model also answers (top/probe.hpp).

topconf::RunResult run_like_arduPilots_simulators(top::Model m, topconf::RunOptions o = {}) {
  topsim::ServerConfig cfg;
  cfg.model = m;
  cfg.device_options.reply_order = top::Order::request_order;
  cfg.device_options.push_order = top::Order::request_order;
  std::string err;
  cfg.faults = topsim::parse_faults("ignore=VER+AWB", err).value();
  RunningServer s(cfg);
  auto t = topconf::open_transport("udp://127.0.0.1:" + std::to_string(s.server.port()), m, 0);
  o.settle_ms = 3;
  return topconf::run_matrix(default_matrix(m), *t, o);
}

std::string console(const topconf::RunResult& r) {
  std::ostringstream os;
  topconf::write_console(os, r, false);
  return os.str();
}

TEST(LikeArduPilotsSimulators, SipAndC12AreReachedOverUdp) {
  for (const auto& [m, note] : {std::pair{top::Model::sip, "probe unanswered: VER"},
                                std::pair{top::Model::c12, "probe unanswered: AWB, VER"}}) {
    const topconf::RunResult r = run_like_arduPilots_simulators(m);
    EXPECT_FALSE(r.unreachable) << r.unreachable_reason;
    EXPECT_EQ(r.probe_note, note);
    EXPECT_FALSE(r.cases.empty());
    EXPECT_EQ(r.count(Verdict::error), 0u);  // alive between cases
    const std::string out = console(r);
    EXPECT_EQ(out.find("unreachable"), std::string::npos) << out;
    EXPECT_NE(out.find(note), std::string::npos) << out;
  }
}

TEST(LikeArduPilotsSimulators, AnUnansweredProbeIsReportedWhenNothingElseFails) {
  topconf::RunOptions o;
  o.tags = {"negative"};  // Topotek: silence for what it does not take
  const topconf::RunResult r = run_like_arduPilots_simulators(top::Model::sip, o);
  EXPECT_EQ(r.exit_code(), 0) << console(r);
  EXPECT_EQ(r.count(Verdict::fail), 0u);
  const std::string out = console(r);
  EXPECT_NE(out.find("\nprobe unanswered: VER\nPASS"), std::string::npos) << out;
  EXPECT_EQ(topconf::to_json(r)["probe_note"], "probe unanswered: VER");
}

// ---- the binaries

TEST(Binaries, TopconfAgainstTopsimOverUdpAndExitCodes) {
  std::string line;
  const pid_t pid = start_topsim({"--model", "c12", "--udp", "127.0.0.1:0"}, line);
  ASSERT_GT(pid, 0);
  ASSERT_EQ(line.rfind("udp 127.0.0.1:", 0), 0u) << line;
  const std::string target = "udp://" + line.substr(4);
  const std::string json = std::string(TOPKIT_BINARY_DIR) + "/topconf_e2e.json";
  EXPECT_EQ(run_cmd(bin("topconf") + " run --model c12 --target " + target +
                    " --settle-ms 3 --json " + json),
            0);
  auto j = nlohmann::json::parse(read_text(json));
  EXPECT_EQ(j["exit_code"], 0);
  EXPECT_GT(j["cases"].size(), 50u);
  std::remove(json.c_str());
  kill(pid, SIGTERM);
  int st = 0;
  waitpid(pid, &st, 0);
  EXPECT_TRUE(WIFEXITED(st));
  // Nobody listens there now: unreachable.
  EXPECT_EQ(run_cmd(bin("topconf") + " run --model c12 --target " + target), 2);
  EXPECT_EQ(run_cmd(bin("topconf") + " run --model c12 --target bogus://x"), 2);
  EXPECT_EQ(run_cmd(bin("topconf") + " run --model c99"), 2);
  EXPECT_EQ(run_cmd(bin("topconf") + " run"), 2);
  EXPECT_EQ(run_cmd(bin("topsim") + " --fault nonsense"), 2);
  EXPECT_EQ(run_cmd(bin("topsim") + " --fault ignore=VE"), 2);
  // In process with a fault: the run fails.
  EXPECT_EQ(run_cmd(bin("topconf") + " run --model c12 --sim-fault bad-checksum=1"), 1);
  EXPECT_EQ(run_cmd(bin("topconf") + " run --model sip"), 0);
}

TEST(Binaries, TopconfWritesEveryReportAndRejectsABadMatrix) {
  const std::string dir = std::string(TOPKIT_BINARY_DIR) + "/topconf_cli_test";
  ASSERT_EQ(run_cmd("mkdir -p " + dir), 0);
  EXPECT_EQ(
      run_cmd(bin("topconf") + " run --model c20 --seed 3 --json " + dir + "/r.json --junit " +
              dir + "/r.xml --html " + dir + "/r.html --pcap " + dir + "/r.pcap"),
      0);
  EXPECT_NE(read_text(dir + "/r.xml").find("<testsuite name=\"topconf.c20\""), std::string::npos);
  EXPECT_NE(read_text(dir + "/r.html").find("<h1>topconf report: c20</h1>"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(read_text(dir + "/r.json"))["seed"], 3);
  int lt = 0;
  EXPECT_GT(payloads(dir + "/r.pcap", lt).size(), 100u);
  // A matrix with a typo: the error names the file, the case and the key.
  std::string bad = read_text(matrix_path("c20"));
  bad.replace(bad.find("\"level\": \"must\""), 15, "\"level\": \"mus\"");
  { std::ofstream(dir + "/bad.json") << bad; }
  EXPECT_EQ(run_cmd(bin("topconf") + " run --model c20 --matrix " + dir + "/bad.json"), 2);
  const int rc = std::system(
      (bin("topconf") + " validate " + dir + "/bad.json 2>" + dir + "/err.txt").c_str());
  EXPECT_EQ(WEXITSTATUS(rc), 1);
  EXPECT_NE(read_text(dir + "/err.txt")
                .find("bad.json: case skydroid/3.1/PTZ/write: level: must be must, should or may"),
            std::string::npos)
      << read_text(dir + "/err.txt");
  run_cmd("rm -rf " + dir);
}

TEST(Binaries, TopsimPtyPrintsItsPath) {
  std::string line;
  const pid_t pid = start_topsim({"--model", "c20", "--pty"}, line);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(line.rfind("/dev/pts/", 0), 0u) << line;
  EXPECT_EQ(run_cmd(bin("topconf") + " run --model c20 --settle-ms 3 --target serial:" + line +
                    "@115200"),
            0);
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
}

}  // namespace
