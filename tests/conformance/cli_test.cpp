// topsim's and topconf's command lines, run as built: a failed write to
// standard output is exit status 2 with a message on every path, and
// topsim --verbose logs each datagram it receives and sends.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "binaries.hpp"

namespace {

struct Ran {
  int status = -1;
  std::string err;
};

// Runs `args` through the shell with stdout on /dev/full; stderr kept in a
// file of its own (ctest runs these tests in parallel processes: a shared
// name let one test read another's stderr, or an empty one).
Ran to_dev_full(const std::string& args) {
  std::string err_file = ::testing::TempDir() + "/cli_test_stderr.XXXXXX";
  const int fd = mkstemp(err_file.data());
  EXPECT_GE(fd, 0) << err_file;
  if (fd >= 0) close(fd);
  const int rc = std::system((args + " >/dev/full 2>" + err_file).c_str());
  Ran r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  std::ifstream in(err_file);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  std::remove(err_file.c_str());
  return r;
}

std::string matrix_file(const char* model) {
  return std::string(TOPKIT_SOURCE_DIR) + "/conformance/matrices/" + model + ".json";
}

class StdoutFull : public ::testing::TestWithParam<std::string> {};

TEST_P(StdoutFull, ExitsTwoWithAMessage) {
  const Ran r = to_dev_full(bin("topconf") + " " + GetParam());
  EXPECT_EQ(r.status, 2) << GetParam() << "\nstderr: " << r.err;
  EXPECT_NE(r.err.find("write error on standard output"), std::string::npos)
      << GetParam() << "\nstderr: " << r.err;
}

INSTANTIATE_TEST_SUITE_P(Topconf, StdoutFull,
                         ::testing::Values("generate --model c12", "generate --model sip", "models",
                                           "validate " + matrix_file("c12"),
                                           "run --model c12 --case 'skydroid/3.1/*' -q",
                                           "fuzz --model c12 --target sim --cases 5 -q",
                                           "--version", "--help"));

TEST(StdoutFull, TopsimDescribeAndVersion) {
  for (const char* args : {" --describe", " --version", " --help"}) {
    const Ran r = to_dev_full(bin("topsim") + args);
    EXPECT_EQ(r.status, 2) << args << "\nstderr: " << r.err;
    EXPECT_NE(r.err.find("write error on standard output"), std::string::npos)
        << args << "\nstderr: " << r.err;
  }
}

// A usage error is exit status 2 and one line "TOOL: error: ..." with no
// timestamp.
TEST(CliErrors, ModelIsCheckedAgainstTheCatalogWithOneFormat) {
  for (const char* tool : {"topsim", "topconf"}) {
    const std::string args =
        std::string(tool) == "topsim" ? " --model c99" : " generate --model c99";
    const Ran r = to_dev_full(bin(tool) + args);
    EXPECT_EQ(r.status, 2) << tool << ": " << r.err;
    EXPECT_EQ(r.err.rfind(std::string(tool) + ": error: --model c99", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("c12"), std::string::npos) << r.err;
  }
}

// topsim's other named values (profile, traits, fault kinds) go through the
// same check as --model: "topsim: error: OPTION VALUE: not one of ...", exit 2.
TEST(CliErrors, TopsimEnumOptionsAreCheckedWithTheSameFormat) {
  struct Bad {
    const char* args;
    const char* message;
    const char* listed;
  };
  for (const Bad& b :
       {Bad{" --profile lab", "--profile lab: not one of ", "field, document"},
        Bad{" --pitch-sign sideways", "--pitch-sign sideways: not one of ", "normal, inverted"},
        Bad{" --push-order any", "--push-order any: not one of ", "swapped, request-order"},
        Bad{" --reply-header TQ", "--reply-header TQ: not one of ", "TP, tp"},
        Bad{" --field-codes yes", "--field-codes yes: not one of ", "on, off"},
        Bad{" --fault drop=0.5,bogus=1", "--fault bogus: not one of ", "drop, delay, duplicate"}}) {
    const Ran r = to_dev_full(bin("topsim") + b.args);
    EXPECT_EQ(r.status, 2) << b.args << ": " << r.err;
    EXPECT_EQ(r.err.rfind(std::string("topsim: error: ") + b.message, 0), 0u) << r.err;
    EXPECT_NE(r.err.find(b.listed), std::string::npos) << r.err;
  }
}

// The build tree's topconf finds the default matrices copied next to it
// (../share/topkit/matrices), as an installed one does.
TEST(Matrices, TheBuildTreeTopconfFindsItsDefaultMatrices) {
  const Ran r = to_dev_full(bin("topconf") + " run --model c12 --case 'skydroid/3.1/*' -q");
  EXPECT_EQ(r.err.find("not found"), std::string::npos) << r.err;
}

// topconf's --sim-fault names go through topsim's check (conformance/cli/fault_arg.hpp).
TEST(CliErrors, TopconfSimFaultNamesAreCheckedAsTopsimsAre) {
  for (const char* args : {" run --model c12 -q --sim-fault drop=1,bogus",
                           " fuzz --model c12 --target sim --cases 1 -q --sim-fault bogus=2"}) {
    const Ran r = to_dev_full(bin("topconf") + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find("topconf: error: --sim-fault bogus: not one of drop, delay"),
              std::string::npos)
        << r.err;
  }
}

// topsim -v on UDP: a datagram received and the reply sent, each logged on
// stderr with its direction, the peer and the bytes.
TEST(TopsimVerbose, LogsEachDatagramReceivedAndSent) {
  int out_pipe[2], err_pipe[2];
  ASSERT_EQ(pipe(out_pipe), 0);
  ASSERT_EQ(pipe(err_pipe), 0);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    dup2(out_pipe[1], 1);
    dup2(err_pipe[1], 2);
    close(out_pipe[0]);
    close(err_pipe[0]);
    std::string exe = bin("topsim");
    std::vector<std::string> args = {exe, "--model", "c12", "--udp", "127.0.0.1:0", "-v"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  close(out_pipe[1]);
  close(err_pipe[1]);
  std::string line;
  char c;
  while (read(out_pipe[0], &c, 1) == 1 && c != '\n') line.push_back(c);
  const auto colon = line.rfind(':');
  ASSERT_NE(colon, std::string::npos) << line;
  const int port = std::stoi(line.substr(colon + 1));

  const int s = socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(s, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const std::string framed = "#TPUD2rVER00";
  unsigned sum = 0;
  for (unsigned char ch : framed) sum += ch;
  char cs[3];
  std::snprintf(cs, sizeof cs, "%02X", sum % 256);
  const std::string sent = framed + cs;
  ASSERT_EQ(sendto(s, sent.data(), sent.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to),
            static_cast<ssize_t>(sent.size()));
  pollfd p{s, POLLIN, 0};
  ASSERT_EQ(poll(&p, 1, 3000), 1) << "no reply";
  char buf[512];
  const ssize_t n = recv(s, buf, sizeof buf, 0);
  ASSERT_GT(n, 0);
  const std::string reply(buf, static_cast<std::size_t>(n));
  sockaddr_in me{};
  socklen_t len = sizeof me;
  getsockname(s, reinterpret_cast<sockaddr*>(&me), &len);
  const std::string peer = "127.0.0.1:" + std::to_string(ntohs(me.sin_port));

  // Read stderr until both lines are there (or 3 s).
  std::string err;
  fcntl(err_pipe[0], F_SETFL, O_NONBLOCK);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (std::chrono::steady_clock::now() < until &&
         (err.find(reply) == std::string::npos || err.find(sent) == std::string::npos)) {
    pollfd e{err_pipe[0], POLLIN, 0};
    if (poll(&e, 1, 100) > 0) {
      const ssize_t k = read(err_pipe[0], buf, sizeof buf);
      if (k > 0) err.append(buf, static_cast<std::size_t>(k));
    }
  }
  kill(pid, SIGTERM);
  int st = 0;
  waitpid(pid, &st, 0);
  close(s);
  close(out_pipe[0]);
  close(err_pipe[0]);

  // "udp < 127.0.0.1:PORT 12 bytes: #TPUD2rVER00.." and "udp > ..." lines.
  auto line_with = [&](const std::string& what) {
    const auto at = err.find(what);
    if (at == std::string::npos) return std::string();
    const auto b = err.rfind('\n', at);
    const auto e = err.find('\n', at);
    return err.substr(b == std::string::npos ? 0 : b + 1,
                      e == std::string::npos ? std::string::npos : e - b - 1);
  };
  const std::string in = line_with(sent);
  const std::string out = line_with(reply);
  EXPECT_NE(in.find("udp <"), std::string::npos) << err;
  EXPECT_NE(in.find(peer), std::string::npos) << err;
  EXPECT_NE(out.find("udp >"), std::string::npos) << err;
  EXPECT_NE(out.find(peer), std::string::npos) << err;
}

}  // namespace
