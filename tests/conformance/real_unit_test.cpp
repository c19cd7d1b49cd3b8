// topsim's sip as the real Topotek camera over real UDP sockets (the traits
// ephemeral_reply_port, fan_out, duplicate_to_client_port and silent_writes
// of top::traits()): where its datagrams go, from which port, how many
// copies, that a write takes effect without an answer, that each switch
// restores the document's behaviour, what a pseudo-terminal keeps, and what
// the command line says of it. Every server runs on its model's port of a
// loopback host of the test's own (loopback.hpp), beside sockets bound there
// as its clients, UDP 9004 among them.
//
// No wait here decides a verdict by timing: "nothing came" is read once a
// later datagram came (a fence: the server is one thread and sends each
// datagram's copies by one system call, so what it sent before the fence is
// queued at its socket when the fence arrives).
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "binaries.hpp"
#include "driver_harness.hpp"
#include "loopback.hpp"
#include "running_server.hpp"
#include "sim/server.hpp"
#include "top/device.hpp"
#include "top/dialect.hpp"
#include "top/frame.hpp"
#include "udp_sock.hpp"

namespace {

const std::uint16_t kClient = top::client_port(top::Model::sip);  // 9004

// topsim --model sip on UDP 9003 of a host of its own, with `o`.
struct Sip {
  explicit Sip(topsim::DeviceOptions o = {})
      : host(own_loopback()), server(config(host, std::move(o))) {}
  // With one switch of the device options set: Sip(&DeviceOptions::fan_out, false).
  template <class T, class V>
  Sip(T topsim::DeviceOptions::*option, V value) : Sip(set(option, value)) {}
  template <class T, class V>
  static topsim::DeviceOptions set(T topsim::DeviceOptions::*option, V value) {
    topsim::DeviceOptions o;
    o.*option = value;
    return o;
  }
  static topsim::ServerConfig config(const std::string& host, topsim::DeviceOptions o) {
    topsim::ServerConfig cfg;
    cfg.model = top::Model::sip;
    cfg.host = host;
    cfg.port = topsim::default_port(top::Model::sip);
    cfg.device_options = std::move(o);
    return cfg;
  }
  std::uint16_t port() const { return server.server.port(); }
  std::string host;
  RunningServer server;
};

constexpr const char* kTrcRead = "#TPPD2rTRC00";

// The sip (with what Sip takes: a switch of its device options) and its two
// clients on the sip's host, both bound, or the test fails here: A, an
// asker on a port of its own, and C on the client port 9004. A test takes
// them as `auto [sip, a, c] = SipAndClients(...)`.
struct SipAndClients {
  template <class... Args>
  explicit SipAndClients(Args&&... args) : sip(std::forward<Args>(args)...) {
    if (!a.ok || !c.ok) throw std::runtime_error("cannot bind A and 9004 on " + sip.host);
  }
  Sip sip;
  Sock a{sip.host}, c{sip.host, kClient};
};

TEST(RealUnit, AReplyLeavesFromItsOwnPortTo9004TwiceTheAskerAndThePortThatAskedBefore) {
  Sip sip;
  Sock a(sip.host), c(sip.host, kClient), b(sip.host);
  ASSERT_TRUE(a.ok && c.ok && b.ok);
  ASSERT_EQ(sip.port(), 9003);
  const std::uint16_t reply_port = sip.server.server.reply_from_port();
  ASSERT_NE(reply_port, 0);
  EXPECT_NE(reply_port, sip.port());

  // A asks: A once, 9004 twice, all from the reply port.
  a.send(kTrcRead, sip.port());
  const auto at_a = a.until_n("TRC", 1);
  const auto at_c = c.until_n("TRC", 2);
  ASSERT_EQ(at_a.size(), 1u);
  ASSERT_EQ(at_c.size(), 2u);
  for (const Datagram& d : at_a) EXPECT_EQ(d.from, reply_port);
  for (const Datagram& d : at_c) EXPECT_EQ(d.from, reply_port);
  EXPECT_EQ(at_c[0].bytes, at_a[0].bytes);
  EXPECT_EQ(at_c[1].bytes, at_a[0].bytes);

  // 9004 asks: 9004 twice (its own copy one of them), A once: the port that
  // asked before it.
  c.send(kTrcRead, sip.port());
  EXPECT_EQ(c.until_n("TRC", 2).size(), 2u);
  EXPECT_EQ(a.until_n("TRC", 1).size(), 1u);

  // B asks: B once, 9004 twice; A no more (sim/fanout.hpp). 9004's fence
  // (VER): every copy sent before it is queued by the time it comes.
  b.send(kTrcRead, sip.port());
  EXPECT_EQ(b.until_n("TRC", 1).size(), 1u);
  EXPECT_EQ(c.until_n("TRC", 2).size(), 2u);
  c.send("#TPPG2rVER00", sip.port());
  const auto fence = c.until_n("VER", 2);
  EXPECT_EQ(count(fence, "TRC"), 0u);
  EXPECT_TRUE(a.queued().empty());
  EXPECT_EQ(count(b.until_n("VER", 1), "VER"), 1u);  // B is the last other asker
}

TEST(RealUnit, AWriteGetsNoAnswerAndTakesEffect) {
  auto [sip, a, c] = SipAndClients();
  // TRC 02 (prepare) then a TRC read: the read's answer is the first thing
  // that comes, and reads the new state (01, waiting), as the camera did
  // (silent_writes evidence).
  a.send("#TPPD2wTRC02", sip.port());
  a.send(kTrcRead, sip.port());
  const auto got = a.until_n("TRC", 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(top::parse_exact(got[0].bytes).frame.control, 'r') << got[0].bytes;
  EXPECT_EQ(top::parse_exact(got[0].bytes).frame.data(), "01") << got[0].bytes;
  // 9004 too got no echo of the write, only the read's two copies.
  const auto at_c = c.until_n("TRC", 2);
  ASSERT_EQ(at_c.size(), 2u);
  for (const Datagram& d : at_c) EXPECT_EQ(top::parse_exact(d.bytes).frame.control, 'r');
  // PTZ (the camera's own silent writes): nothing before the GIC query's answer.
  a.send("#TPPG2wPTZ04", sip.port());
  a.send("#TPPG2wPTZ00", sip.port());
  a.send("#TPPG2rGIC00", sip.port());
  EXPECT_EQ(a.until_n("GIA", 1).size(), 1u);
}

TEST(RealUnit, PushesGoWhereTheRepliesGo) {
  auto [sip, a, c] = SipAndClients();
  // GIA 01 from A: 10 Hz GIA to A once and to 9004 twice, from the reply port.
  a.send("#TPPG2wGIA01", sip.port());
  const auto first = a.until_n("GIA", 3);
  EXPECT_EQ(count(first, "GIA"), 3u);
  for (const Datagram& d : first) EXPECT_EQ(d.from, sip.server.server.reply_from_port());
  a.send("#TPPG2wGIA00", sip.port());
  a.send(kTrcRead, sip.port());  // the fence: after the stream stopped
  const auto rest_a = a.until_n("TRC", 1);
  const auto all_c = c.until_n("TRC", 2);
  const std::size_t pushes = count(first, "GIA") + count(rest_a, "GIA");
  EXPECT_EQ(count(all_c, "GIA"), 2 * pushes);
  EXPECT_TRUE(a.queued().empty());
}

// Each switch restores the document's behaviour, one at a time.
TEST(RealUnit, ReplyFromServedAnswersFromPort9003) {
  Sip sip(&topsim::DeviceOptions::ephemeral_reply_port, false);
  Sock a(sip.host);
  ASSERT_TRUE(a.ok);
  EXPECT_EQ(sip.server.server.reply_from_port(), 0);
  a.send(kTrcRead, sip.port());
  const auto got = a.until_n("TRC", 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].from, sip.port());
}

TEST(RealUnit, FanOutOffAnswersOnly9004) {
  auto [sip, a, c] = SipAndClients(&topsim::DeviceOptions::fan_out, false);
  a.send(kTrcRead, sip.port());
  EXPECT_EQ(c.until_n("TRC", 2).size(), 2u);
  c.send("#TPPG2rVER00", sip.port());
  EXPECT_EQ(count(c.until_n("VER", 2), "VER"), 2u);
  EXPECT_TRUE(a.queued().empty());  // the asker got nothing
}

TEST(RealUnit, DuplicateOffSendsOneCopyTo9004) {
  auto [sip, a, c] = SipAndClients(&topsim::DeviceOptions::duplicate, false);
  // A's TRC read, 9004's VER read, then A's GIC query as the fence: 9004
  // has each answer once.
  a.send(kTrcRead, sip.port());
  EXPECT_EQ(a.until_n("TRC", 1).size(), 1u);
  c.send("#TPPG2rVER00", sip.port());
  a.send("#TPPG2rGIC00", sip.port());
  const auto at_c = c.until_n("GIA", 1);
  EXPECT_EQ(count(at_c, "TRC"), 1u);
  EXPECT_EQ(count(at_c, "VER"), 1u);
  EXPECT_EQ(at_c.size(), 3u);
}

TEST(RealUnit, WriteEchoOnEchoesTheWrite) {
  Sip sip(&topsim::DeviceOptions::write_echo, true);
  Sock a(sip.host);
  ASSERT_TRUE(a.ok);
  a.send("#TPPD2wTRC02", sip.port());
  const auto got = a.until_n("TRC", 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].bytes, top::with_checksum("#TPDP2wTRC02"));
}

TEST(RealUnit, TheDocumentProfileAnswersFrom9003To9004OnceAndNoWrite) {
  auto [sip, a, c] = SipAndClients(&topsim::DeviceOptions::profile, top::Profile::document);
  EXPECT_EQ(sip.server.server.reply_from_port(), 0);
  // A zoom write the document gives no reply form, then the version read:
  // 9004 gets the read's answer once, from 9003, and nothing else.
  a.send("#TPPM2wZMC01", sip.port());
  a.send("#TPPG2rVER00", sip.port());
  const auto at_c = c.until_n("VER", 1);
  ASSERT_EQ(at_c.size(), 1u);
  EXPECT_EQ(at_c[0].from, sip.port());
  c.send("#TPPG2rVER00", sip.port());  // fence
  EXPECT_EQ(c.until_n("VER", 1).size(), 1u);
  EXPECT_TRUE(c.queued().empty());
  EXPECT_TRUE(a.queued().empty());
}

TEST(RealUnit, APseudoTerminalHasNoPortsAndItsWritesAreSilent) {
  topsim::ServerConfig cfg;
  cfg.model = top::Model::sip;
  cfg.kind = topsim::TransportKind::pty;
  RunningServer s(cfg);
  const int fd = ::open(s.server.pty_path().c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(fd, 0);
  termios t{};
  ::tcgetattr(fd, &t);
  ::cfmakeraw(&t);
  ::tcsetattr(fd, TCSANOW, &t);
  // UART: the client is U. The write, then the read: one answer, the read's.
  const std::string w = top::with_checksum("#TPUD2wTRC02"), r = top::with_checksum("#TPUD2rTRC00");
  ASSERT_EQ(::write(fd, w.data(), w.size()), static_cast<ssize_t>(w.size()));
  ASSERT_EQ(::write(fd, r.data(), r.size()), static_cast<ssize_t>(r.size()));
  std::string all;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (all.size() < 14 && std::chrono::steady_clock::now() < end) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 50) <= 0) continue;
    char buf[256];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) all.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  EXPECT_EQ(all, top::with_checksum("#TPDU2rTRC01"));
  EXPECT_EQ(s.server.reply_from_port(), 0);
}

// ---- the command line

// Starts topsim with `args`, stderr to the file `err`; returns its pid (to
// be stopped) and its first stdout line.
pid_t start_logging(const std::vector<std::string>& args, const std::string& err,
                    std::string& line) {
  const std::string exe = bin("topsim");
  int out[2];
  if (::pipe(out) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], 1);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(e, 2);
    ::close(out[0]);
    std::vector<std::string> copy = args;
    std::vector<char*> argv{const_cast<char*>(exe.c_str())};
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(out[1]);
  char ch;
  while (::read(out[0], &ch, 1) == 1 && ch != '\n') line.push_back(ch);
  ::close(out[0]);
  return pid;
}

std::string read_file(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

TEST(RealUnitCli, TheStartupLogAndVerboseNameTheReplyPort) {
  const std::string host = own_loopback();
  const std::string err = std::string(TOPKIT_BINARY_DIR) + "/real_unit_cli.err";
  std::string line;
  const pid_t pid = start_logging({"--model", "sip", "--udp", host + ":9003", "-v"}, err, line);
  ASSERT_GT(pid, 0);
  ASSERT_EQ(line, "udp " + host + ":9003");
  {
    Sock a(host);
    a.send(kTrcRead, 9003);
    const auto got = a.until_n("TRC", 1);
    ASSERT_EQ(got.size(), 1u);
    const std::string from = " from port " + std::to_string(got[0].from) + " ";
    // -v: each copy, to the asker and twice to 9004, from the reply port
    const std::string to_client = "udp > " + host + ":9004" + from;
    auto copies = [&](const std::string& log) {
      std::size_t n = 0;
      for (auto at = log.find(to_client); at != std::string::npos; at = log.find(to_client, at + 1))
        ++n;
      return n;
    };
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    std::string log = read_file(err);
    while (std::chrono::steady_clock::now() < end && copies(log) < 2) {
      ::usleep(20000);
      log = read_file(err);
    }
    EXPECT_EQ(copies(log), 2u) << log;
    EXPECT_NE(log.find("replies from port " + std::to_string(got[0].from) +
                       " to port 9004 twice and to the last other port that asked"),
              std::string::npos)
        << log;
    EXPECT_NE(log.find("udp > " + host + ":" + std::to_string(a.port()) + from), std::string::npos)
        << log;
  }
  ::kill(pid, SIGTERM);
  ::waitpid(pid, nullptr, 0);
  std::remove(err.c_str());
}

// `topsim --describe`: each UDP trait and the silent writes with its
// source, read from top::traits(); each switch shown as the option.
TEST(RealUnitCli, DescribeNamesEachTraitsSourceAndItsSwitch) {
  auto describe = [](const std::string& args) {
    std::string out;
    FILE* f = ::popen((bin("topsim") + " --model sip --describe " + args).c_str(), "r");
    char buf[4096];
    for (std::size_t n; f && (n = std::fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
    if (f) ::pclose(f);
    return out;
  };
  auto row = [](const std::string& out, const std::string& name) {
    const auto at = out.find("  " + name + " ");
    return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
  };
  const std::string field = describe("");
  for (top::TraitKind k :
       {top::TraitKind::ephemeral_reply_port, top::TraitKind::fan_out,
        top::TraitKind::duplicate_to_client_port, top::TraitKind::silent_writes}) {
    const top::Trait* t = top::find_trait(k, top::Model::sip, top::Profile::field);
    ASSERT_NE(t, nullptr);
    EXPECT_NE(field.find(std::string(t->evidence)), std::string::npos) << top::to_string(k);
  }
  EXPECT_NE(row(field, "reply-from").find("ephemeral"), std::string::npos) << field;
  EXPECT_NE(row(field, "fan-out").find(" on "), std::string::npos) << field;
  EXPECT_NE(row(field, "duplicate").find(" on "), std::string::npos) << field;
  EXPECT_NE(row(field, "write-echo").find(" off "), std::string::npos) << field;
  EXPECT_NE(row(field, "fan-out").find("field"), std::string::npos) << field;
  const std::string doc = describe("--profile document");
  EXPECT_NE(row(doc, "reply-from").find("served"), std::string::npos) << doc;
  EXPECT_NE(row(doc, "reply-from").find("document rule"), std::string::npos) << doc;
  EXPECT_NE(row(doc, "fan-out").find("Topotek V1.1.3"), std::string::npos) << doc;
  const std::string sw =
      describe("--reply-from served --fan-out off --duplicate off --write-echo on");
  for (const char* name : {"reply-from", "fan-out", "duplicate", "write-echo"})
    EXPECT_NE(row(sw, name).find("option"), std::string::npos) << name << "\n" << sw;
  EXPECT_NE(row(sw, "write-echo").find(" on "), std::string::npos) << sw;
  EXPECT_EQ(run_cmd(bin("topsim") + " --model sip --fan-out sideways --describe"), 2);
}

// topconf run --model sip against `topsim --model sip` as it starts, over
// real UDP: bound as it binds by default (UDP 9004 of the target's host)
// and on an ephemeral port, no case fails and none is flaky.
TEST(RealUnitCli, TopconfRunPassesAgainstTheDefaultSip) {
  const std::string host = own_loopback();
  std::string line;
  const pid_t pid = start_topsim({"--model", "sip", "--udp", host + ":9003"}, line);
  ASSERT_GT(pid, 0);
  ASSERT_EQ(line, "udp " + host + ":9003");
  for (const char* bind : {"", " --bind 0"}) {
    const std::string json = std::string(TOPKIT_BINARY_DIR) + "/real_unit_topconf.json";
    EXPECT_EQ(run_cmd(bin("topconf") + " run --model sip --target udp://" + host + ":9003" + bind +
                      " --json " + json),
              0)
        << bind;
    const auto j = nlohmann::json::parse(read_file(json), nullptr, false);
    ASSERT_TRUE(j.is_object()) << bind;
    EXPECT_GT(j["cases"].size(), 100u);
    for (const auto& c : j["cases"]) {
      const std::string result = c.value("result", ""), reason = c.value("reason", "");
      // a plain pass, or a form the field records (docs/FIELD.md)
      EXPECT_TRUE(result == "pass" ||
                  (result == "non-strict" && reason.find("the field's form") != std::string::npos))
          << bind << " " << c.value("id", "") << ": " << result << " " << reason;
      EXPECT_FALSE(c.value("flaky", true)) << bind << " " << c.value("id", "");
    }
    std::remove(json.c_str());
  }
  ::kill(pid, SIGTERM);
  ::waitpid(pid, nullptr, 0);
}

}  // namespace

namespace {

// topsim's default sip recorded and read back by topdump says what it says
// of the real camera's sessions (captures/sip-bench): a client that polls
// as the PixEagle bench does, from three ports of its host (9004 among
// them), stops, pulses yaw with the bench's U source and prepares, cancels
// and disables tracking; every query paired, the copies counted once, the
// reply port, the fan-out and the silent writes noted once, the client's U
// named, and nothing else above info.
TEST(RealUnit, ItsRecordingReadsAsTheRealCamerasSessionsDo) {
  for (const bool u_source : {true, false}) {
    SCOPED_TRACE(u_source ? "with the bench's U source" : "with P only");
    const std::string rec =
        std::string(TOPKIT_BINARY_DIR) + "/real_unit_bench_" + (u_source ? "u" : "p") + ".pcap";
    std::size_t reads = 0;
    {
      topsim::ServerConfig cfg = Sip::config(own_loopback(), {});
      cfg.record = rec;
      const std::string host = cfg.host;
      RunningServer server(std::move(cfg));
      Sock a(host), b(host, kClient), c(host);
      // a read and its answer, awaited on the asking socket
      auto read = [&](Sock& s, const char* body, const char* answer) {
        s.send(body, 9003);
        s.until_n(answer, 1);
        ++reads;
      };
      for (int i = 0; i < 3; ++i) {
        read(a, kTrcRead, "TRC");
        read(a, "#TPPG2rGAC00", "GAC");
      }
      read(b, "#TPPG2rGIC00", "GIA");  // from 9004, answered with GIA
      read(c, kTrcRead, "TRC");
      for (const char* w : {"#TPPG2wPTZ00", "#TPPG2wPTZ00", "#TPPM2wZMC00", "#TPPM2wZMC00"})
        a.send(w, 9003);
      a.send(u_source ? "#TPUG2wGSY05" : "#TPPG2wGSY05", 9003);
      read(a, "#TPPG2rGAC00", "GAC");
      a.send("#TPPG2wPTZ00", 9003);
      for (const char* w : {"#TPPD2wTRC02", "#TPPD2wTRC01", "#TPPD2wTRC00"}) {
        a.send(w, 9003);
        read(a, kTrcRead, "TRC");
      }
    }
    const JsonLines run = topdump_read_json(rec);
    std::size_t paired = 0, copies = 0, queries = 0;
    std::map<std::string, int> notes;
    for (const auto& [line, j] : run.lines) {
      ASSERT_FALSE(j.is_discarded()) << line;
      if (j.value("type", "") == "frame") {
        if (!j["reply_to"].is_null()) ++paired;
        if (!j["copy_of"].is_null()) ++copies;
        if (j.value("control", "") == "r" && j["role"] == "request") ++queries;
        for (const auto& f : j["findings"]) EXPECT_EQ(f["severity"], "info") << line;
        for (const auto& s : j["session"]) EXPECT_EQ(s["code"], "repeated") << line;
      } else if (j.value("type", "") == "finding") {
        ++notes[j.value("code", "")];
        if (j.value("severity", "") != "info") {
          EXPECT_EQ(j["code"], "reply-interface") << line;
        }
      }
    }
    EXPECT_EQ(queries, reads);
    EXPECT_EQ(paired, reads);
    EXPECT_GE(copies, reads * 2);  // 9004 twice and the asker, at least
    EXPECT_EQ(notes["reply-port"], 1);
    EXPECT_EQ(notes["fan-out"], 1);
    EXPECT_EQ(notes["silent-writes"], 1);
    EXPECT_EQ(notes["unanswered"], 0);
    EXPECT_EQ(notes["reply-interface"], u_source ? 1 : 0);
    EXPECT_EQ(run.status, u_source ? 1 : 0);
    if (!HasFailure()) std::remove(rec.c_str());
  }
}

}  // namespace
