// Live sources: `topdump serial` on a real pseudo-terminal pair, ended by
// SIGINT; live capture on lo through libpcap when this process may capture.
#include "capture/live.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"
#include "test_support.hpp"
#include "top/frame.hpp"

namespace topdump::test {
namespace {

TEST(Live, SerialOverAPseudoTerminalEndsCleanlyOnSigint) {
  int master = -1, slave = -1;
  char name[128] = {0};
  ASSERT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0) << "openpty failed";
  int out[2];
  ASSERT_EQ(pipe(out), 0);
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    dup2(out[1], 1);
    close(out[0]);
    close(master);
    std::string bin = topdump_bin();
    execl(bin.c_str(), bin.c_str(), "serial", "--baud", "115200", name,
          static_cast<char*>(nullptr));
    _exit(127);
  }
  close(out[1]);
  std::string acc;
  // write until topdump has opened the port and decoded a frame
  std::string f1 = top::with_checksum("#TPGUCrGAC0000FED40000"),
              f2 = top::with_checksum("#TPGU2wPTZ05");
  bool seen = false;
  for (int i = 0; i < 40 && !seen; ++i) {
    ASSERT_EQ(::write(master, f1.data(), f1.size()), static_cast<ssize_t>(f1.size()));
    ASSERT_EQ(::write(master, f2.substr(0, 5).data(), 5), 5);  // a frame split across writes
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_EQ(::write(master, f2.substr(5).data(), f2.size() - 5),
              static_cast<ssize_t>(f2.size() - 5));
    seen = read_until(out[0], acc, "PTZ response", 250);
  }
  EXPECT_TRUE(seen) << acc;
  EXPECT_NE(acc.find("GAC response"), std::string::npos) << acc;
  kill(pid, SIGINT);
  read_until(out[0], acc, "pairing:", 5000);
  int st = 0;
  for (int i = 0; i < 50 && waitpid(pid, &st, WNOHANG) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  if (waitpid(pid, &st, WNOHANG) == 0 && !WIFEXITED(st)) {
    kill(pid, SIGKILL);
    waitpid(pid, &st, 0);
    FAIL() << "topdump serial did not end on SIGINT";
  }
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 0) << acc;
  EXPECT_NE(acc.find("-- statistics"), std::string::npos) << acc;
  EXPECT_NE(acc.find("per identifier:"), std::string::npos) << acc;
  close(out[0]);
  close(master);
  close(slave);
}

TEST(Live, SerialBadDeviceIsExit2) {
  std::string out;
  EXPECT_EQ(run("'" + topdump_bin() + "' serial /dev/nonexistent-tty 2>/dev/null", out), 2);
}

struct Counting : Sink {
  std::atomic<int> frames{0};
  void frame(const FrameEvent&) override { ++frames; }
};

TEST(Live, CaptureOnLoopback) {
  Counting sink;
  AnalyzerOptions ao;
  Analyzer a(ao, sink);
  // a port nobody else uses: bind it to learn one
  int s = socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(s, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  socklen_t len = sizeof addr;
  getsockname(s, reinterpret_cast<sockaddr*>(&addr), &len);
  std::uint16_t port = ntohs(addr.sin_port);
  SourceOptions so;
  so.udp_ports.insert(port);
  std::atomic<bool> stop{false}, done{false}, ok{false}, perm{false};
  std::string err;
  std::thread t([&] {
    bool p = false;
    ok = capture_live("lo", "udp port " + std::to_string(port), a, so, stop, err, p);
    perm = p;
    done = true;
  });
  std::string f = top::with_checksum("#TPUG2wPTZ05");
  for (int i = 0; i < 60 && !done && sink.frames == 0; ++i) {
    sendto(s, f.data(), f.size(), 0, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  stop = true;
  t.join();
  close(s);
  if (!ok && (perm || err.find("ermission") != std::string::npos ||
              err.find("not permitted") != std::string::npos))
    GTEST_SKIP() << "no permission to capture on lo (needs root or CAP_NET_RAW): " << err;
  ASSERT_TRUE(ok) << err;
  EXPECT_GT(sink.frames.load(), 0);
}

}  // namespace
}  // namespace topdump::test
