// topdump's input side, run as the built binary: stdin, pipes and FIFOs
// with format detection, damaged and mislabelled captures, the format it
// chose, two serial taps (logs and pseudo-terminals), live CR/LF after the
// FTDI latency, file-level findings printed once, and the messages about
// unreadable input.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <thread>

#include "capture/live.hpp"
#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"
#include "test_support.hpp"
#include "top/frame.hpp"

namespace topdump::test {
namespace {

using namespace pcapio;

std::string q(const std::string& s) { return "'" + s + "'"; }
std::string bin() { return q(topdump_bin()); }
std::string cap_quoted(const std::string& n) { return q(captures_dir() + "/" + n); }

// `bytes` with the 32-bit word at `at` set to `v` (host order, as the
// capture files of these tests are written).
std::string with_u32(std::string bytes, std::size_t at, std::uint32_t v) {
  std::memcpy(bytes.data() + at, &v, 4);
  return bytes;
}

std::size_t count(const std::string& hay, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = hay.find(needle); at != std::string::npos; at = hay.find(needle, at + 1)) ++n;
  return n;
}

// --- 1. pipes ---------------------------------------------------------------

// `out` with every `name` written as "@" (messages name the input).
std::string unnamed(std::string out, const std::string& name) {
  for (auto at = out.find(name); at != std::string::npos; at = out.find(name, at + 1))
    out.replace(at, name.size(), "@");
  return out;
}

TEST(Input, StdinPipesAndFifosReadLikeFiles) {
  std::string file, piped;
  for (const char* c : {"sample.pcap", "multi-if.pcapng", "serial-lines.log", "serial-socat-xv.log",
                        "serial-saleae.csv"}) {
    const int rc = run(bin() + " read " + cap_quoted(c) + " 2>/dev/null", file);
    file = unnamed(file, captures_dir() + "/" + c);
    EXPECT_FALSE(file.empty()) << c;
    EXPECT_EQ(run("cat " + cap_quoted(c) + " | " + bin() + " read - 2>/dev/null", piped), rc) << c;
    EXPECT_EQ(unnamed(piped, "stdin"), file) << c << " through read -";
    EXPECT_EQ(run("cat " + cap_quoted(c) + " | " + bin() + " read /dev/stdin 2>/dev/null", piped),
              rc)
        << c;
    EXPECT_EQ(unnamed(piped, "/dev/stdin"), file) << c << " through /dev/stdin";
    EXPECT_EQ(run("bash -c \"exec 7< <(cat " + cap_quoted(c) + "); " + bin() +
                      " read /dev/fd/7 2>/dev/null\"",
                  piped),
              rc)
        << c;
    EXPECT_EQ(unnamed(piped, "/dev/fd/7"), file) << c << " through a process substitution";
  }
  TempDir tmp;
  const std::string fifo = tmp.file("fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(run("(cat " + cap_quoted("sll.pcap") + " > " + q(fifo) + " &) ; " + bin() + " read " +
                    q(fifo) + " 2>/dev/null",
                piped),
            0);
  run(bin() + " read " + cap_quoted("sll.pcap"), file);
  EXPECT_EQ(piped, file) << "through a FIFO";
  // a pipe that holds less than a pcap file header
  std::string err;
  EXPECT_EQ(run("printf '\\324\\303\\262\\241' | " + bin() + " read - 2>&1", err), 2);
  EXPECT_NE(err.find("stdin: offset 0: the pcap file header is cut short (4 of 24 bytes)"),
            std::string::npos)
      << err;
}

// --- 2. detection says what it chose ----------------------------------------

TEST(Input, DamagedMagicIsADamagedCaptureNotASerialDump) {
  TempDir tmp;
  for (const char* c : {"sample.pcap", "multi-if.pcapng"}) {
    std::string bytes = slurp(captures_dir() + "/" + c);
    bytes[0] = static_cast<char>(bytes[0] ^ 0x01);
    const std::string f = tmp.file(std::string("damaged-") + c);
    write_file(f, bytes);
    std::string out;
    EXPECT_EQ(run(bin() + " read " + q(f) + " 2>&1", out), 2) << c;
    EXPECT_NE(out.find(f + ": offset 0: magic number"), std::string::npos) << out;
    EXPECT_NE(out.find("a damaged capture"), std::string::npos) << out;
    EXPECT_EQ(out.find("#1 "), std::string::npos) << out;
    // asked for, it is still read as a raw dump
    EXPECT_NE(run(bin() + " read --format raw " + q(f) + " 2>&1", out), 2) << out;
  }
}

TEST(Input, FormatThatTheFileIsNotIsAnError) {
  std::string out;
  EXPECT_EQ(run(bin() + " read --format pcapng " + cap_quoted("sample.pcap") + " 2>&1", out), 2);
  EXPECT_NE(out.find("sample.pcap: offset 0: --format pcapng but this is a pcap file"),
            std::string::npos)
      << out;
  EXPECT_EQ(run(bin() + " read --format pcap " + cap_quoted("multi-if.pcapng") + " 2>&1", out), 2);
  EXPECT_NE(out.find("--format pcap but this is a pcapng file"), std::string::npos) << out;
  EXPECT_EQ(
      run(bin() + " read --format pcapng " + cap_quoted("multi-if.pcapng") + " 2>/dev/null", out),
      0);
  EXPECT_EQ(run(bin() + " read --format pcapng " + cap_quoted("serial-lines.log") + " 2>&1", out),
            2);
  EXPECT_NE(out.find("not a pcapng file"), std::string::npos) << out;
}

TEST(Input, TheChosenFormatIsStated) {
  std::string out;
  run(bin() + " read -v " + cap_quoted("sample.pcap") + " 2>&1 >/dev/null", out);
  EXPECT_NE(out.find("sample.pcap: pcap, link type EN10MB"), std::string::npos) << out;
  run(bin() + " read -v " + cap_quoted("serial-lines.log") + " 2>&1 >/dev/null", out);
  EXPECT_NE(out.find("serial-lines.log: lines"), std::string::npos) << out;
  run(bin() + " stats " + cap_quoted("multi-if.pcapng") + " " + cap_quoted("serial-saleae.csv"),
      out);
  EXPECT_NE(out.find("input: " + captures_dir() + "/multi-if.pcapng: pcapng, link type EN10MB"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("input: " + captures_dir() + "/serial-saleae.csv: saleae"), std::string::npos)
      << out;
  run(bin() + " stats --json " + cap_quoted("serial-raw.bin"), out);
  auto j = nlohmann::json::parse(out);
  ASSERT_EQ(j["inputs"].size(), 1u) << out;
  EXPECT_EQ(j["inputs"][0]["format"], "raw");
  EXPECT_TRUE(j["inputs"][0]["link"].is_null());
  run(bin() + " read --json " + cap_quoted("sll2.pcap"), out);
  auto first = nlohmann::json::parse(out.substr(0, out.find('\n')));
  EXPECT_EQ(first["type"], "input");
  EXPECT_EQ(first["format"], "pcap");
  EXPECT_EQ(first["link"], "LINUX_SLL2");
}

// --- 3. two serial taps -------------------------------------------------------

TEST(Input, TwoTimedLogsMergeIntoOneConversation) {
  TempDir tmp;
  // one tap per direction: the autopilot's TX and the gimbal's TX
  const std::string gay = top::with_checksum("#tpUG6wGAYEC7832");
  const std::string ptz = top::with_checksum("#TPUG2wPTZ05");
  write_file(tmp.file("autopilot.log"),
             "2024-05-01T12:00:00.000Z RX " + gay + "\n2024-05-01T12:00:00.100Z RX " + ptz + "\n");
  write_file(tmp.file("gimbal.log"),
             "2024-05-01T12:00:00.012Z RX " + top::with_checksum("#tpGU6wGAYEC7832") +
                 "\n2024-05-01T12:00:00.109Z RX " + top::with_checksum("#TPGU2wPTZ05") + "\n");
  std::string out;
  EXPECT_EQ(run(bin() + " read --json " + q(tmp.file("gimbal.log")) + " " +
                    q(tmp.file("autopilot.log")) + " 2>&1",
                out),
            0)
      << out;
  std::vector<nlohmann::json> frames;
  std::stringstream ss(out);
  for (std::string l; std::getline(ss, l);) {
    auto j = nlohmann::json::parse(l);
    if (j["type"] == "frame") frames.push_back(j);
    EXPECT_NE(j["type"], "finding") << l;
  }
  ASSERT_EQ(frames.size(), 4u) << out;
  EXPECT_EQ(frames[0]["from"], tmp.file("autopilot.log"));
  EXPECT_EQ(frames[0]["to"], tmp.file("gimbal.log"));
  EXPECT_EQ(frames[1]["from"], tmp.file("gimbal.log"));
  EXPECT_EQ(frames[1]["reply_to"], 1);
  EXPECT_DOUBLE_EQ(frames[1]["latency_ms"].get<double>(), 12.0);
  EXPECT_EQ(frames[3]["reply_to"], 3);
  for (const auto& f : frames) EXPECT_EQ(f["conversation"], frames[0]["conversation"]);
  // a bad line of the second log: named once, by its own file
  write_file(tmp.file("bad.log"), "2024-05-01T12:00:00.012Z RX " +
                                      top::with_checksum("#tpGU6wGAYEC7832") + "\nnot a line\n");
  EXPECT_EQ(run(bin() + " read " + q(tmp.file("autopilot.log")) + " " + q(tmp.file("bad.log")) +
                    " 2>&1 >/dev/null",
                out),
            1);
  EXPECT_EQ(count(out, "bad.log"), 1u) << out;
  EXPECT_EQ(count(out, "autopilot.log"), 0u) << out;
  EXPECT_NE(out.find("line 2: expected"), std::string::npos) << out;
  // a raw dump has no times to merge by
  EXPECT_EQ(run(bin() + " read " + q(tmp.file("gimbal.log")) + " " + cap_quoted("serial-raw.bin") +
                    " 2>&1",
                out),
            2);
  EXPECT_NE(out.find("serial-raw.bin: a raw input cannot be merged"), std::string::npos) << out;
}

// `topdump serial` on pseudo-terminals, stdout into a pipe.
struct SerialRun {
  struct Pty {
    int master = -1, slave = -1;
    char name[128] = {0};
  };
  std::vector<Pty> ptys;
  int out = -1;
  pid_t pid = -1;
  std::string acc;
  explicit SerialRun(int n) {
    ptys.resize(static_cast<std::size_t>(n));
    for (auto& p : ptys) {
      if (openpty(&p.master, &p.slave, p.name, nullptr, nullptr) != 0) return;
      // raw: the line discipline must not turn CR into LF
      termios t{};
      tcgetattr(p.slave, &t);
      cfmakeraw(&t);
      tcsetattr(p.slave, TCSANOW, &t);
    }
    int fds[2];
    if (pipe(fds) != 0) return;
    pid = fork();
    if (pid == 0) {
      dup2(fds[1], 1);
      close(fds[0]);
      const std::string b = topdump_bin();
      std::vector<const char*> argv = {b.c_str(), "serial", "--json"};
      for (auto& p : ptys) argv.push_back(p.name);
      argv.push_back(nullptr);
      execv(b.c_str(), const_cast<char* const*>(argv.data()));
      _exit(127);
    }
    close(fds[1]);
    out = fds[0];
  }
  bool ok() const { return pid > 0 && out >= 0; }
  void send(std::size_t i, const std::string& s) {
    ASSERT_EQ(::write(ptys[i].master, s.data(), s.size()), static_cast<ssize_t>(s.size()));
  }
  // Sends `probe` on tap i until topdump shows `seen` (it has opened the
  // port): false after 40 tries.
  bool wait_open(std::size_t i, const std::string& probe, const std::string& seen) {
    for (int k = 0; k < 40; ++k) {
      send(i, probe);
      if (read_until(out, acc, seen, 250)) return true;
    }
    return false;
  }
  // Ends topdump with SIGINT; its exit status.
  int stop() {
    kill(pid, SIGINT);
    read_until(out, acc, "\"type\":\"stats\"", 5000);
    int st = 0;
    for (int i = 0; i < 50 && waitpid(pid, &st, WNOHANG) == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!WIFEXITED(st)) {
      kill(pid, SIGKILL);
      waitpid(pid, &st, 0);
      return -1;
    }
    return WEXITSTATUS(st);
  }
  ~SerialRun() {
    if (out >= 0) close(out);
    for (auto& p : ptys) close(p.master), close(p.slave);
  }
  std::vector<nlohmann::json> frames() const {
    std::vector<nlohmann::json> f;
    std::stringstream ss(acc);
    for (std::string l; std::getline(ss, l);) {
      auto j = nlohmann::json::parse(l, nullptr, false);
      if (!j.is_discarded() && (j["type"] == "frame" || j["type"] == "garbage")) f.push_back(j);
    }
    return f;
  }
};

// Two taps merged are both directions of the line: a gimbal tap with no
// frame is a silent device (silent-device), not a line nobody recorded
// (CaptureSink::both_ways; a one-tap dump stays one way).
TEST(Input, TwoTapsWithASilentGimbalNameIt) {
  TempDir tmp;
  std::string requests;
  for (int i = 0; i < 20; ++i) {
    char t[40];
    std::snprintf(t, sizeof t, "2024-05-01T12:00:%02d.%03dZ TX ", i / 4, (i % 4) * 250);
    requests += t + top::with_checksum("#TPUD2rVER00") + "\n";
  }
  write_file(tmp.file("autopilot.log"), requests);
  write_file(tmp.file("gimbal.log"), "2024-05-01T11:59:59.000Z RX \n");
  std::string out;
  EXPECT_EQ(run(bin() + " read " + q(tmp.file("autopilot.log")) + " " + q(tmp.file("gimbal.log")) +
                    " 2>&1",
                out),
            1);
  EXPECT_NE(out.find("silent-device"), std::string::npos) << out;
}

TEST(Input, TwoSerialTapsPairRequestsAndReplies) {
  SerialRun r(2);
  ASSERT_TRUE(r.ok());
  // wait until topdump has opened both ports: a probe on the first is decoded
  ASSERT_TRUE(r.wait_open(0, top::with_checksum("#TPUG2wVER00"), "\"VER\"")) << r.acc;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  r.send(0, top::with_checksum("#TPUG2wPTZ05"));
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  r.send(1, top::with_checksum("#TPGU2wPTZ05"));
  EXPECT_TRUE(read_until(r.out, r.acc, "\"reply_to\":", 3000)) << r.acc;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(r.stop(), 0) << r.acc;
  std::vector<nlohmann::json> ptz;
  for (const auto& f : r.frames())
    if (f.value("ident", "") == "PTZ") ptz.push_back(f);
  ASSERT_EQ(ptz.size(), 2u) << r.acc;
  EXPECT_EQ(ptz[0]["from"], r.ptys[0].name);
  EXPECT_EQ(ptz[0]["to"], r.ptys[1].name);
  EXPECT_EQ(ptz[1]["from"], r.ptys[1].name);
  EXPECT_EQ(ptz[1]["reply_to"], ptz[0]["n"]);
  EXPECT_EQ(ptz[1]["conversation"], ptz[0]["conversation"]);
  EXPECT_TRUE(ptz[1]["session"].empty()) << ptz[1].dump();
}

// --- 4. live CR/LF after the FTDI latency -------------------------------------

TEST(Input, LiveCrlfWithinTheQuietTimeBelongsToItsFrame) {
  SerialRun r(1);
  ASSERT_TRUE(r.ok());
  const std::string f = top::with_checksum("#TPGU2wPTZ05");
  ASSERT_TRUE(r.wait_open(0, f + "\r\n", "\"PTZ\"")) << r.acc;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  read_until(r.out, r.acc, "never", 50);
  r.acc.clear();
  // an FTDI adapter hands over the CR/LF with the next 16 ms latency tick;
  // eight times, so a periodic flush would fall in one of the gaps. A gap
  // this test stretched past the quiet time (a loaded machine) may give
  // garbage: such gaps are counted, not judged.
  int late = 0;
  for (int i = 0; i < 8; ++i) {
    r.send(0, f);
    const auto sent = std::chrono::steady_clock::now();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    r.send(0, "\r\n");
    if (std::chrono::steady_clock::now() - sent >= kSerialQuiet - std::chrono::milliseconds(10))
      ++late;
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
  }
  EXPECT_EQ(r.stop(), 0) << r.acc;
  ASSERT_LE(late, 2) << "the machine is too loaded to time a 20 ms gap";
  int crlf = 0, garbage = 0;
  for (const auto& j : r.frames()) {
    if (j["type"] == "garbage") ++garbage;
    if (j["type"] != "frame") continue;
    for (const auto& x : j["findings"]) crlf += x["code"] == "crlf";
  }
  EXPECT_LE(garbage, late) << r.acc;
  EXPECT_GE(crlf, 8 - late) << r.acc;
}

// --- 5. raw serial dumps ------------------------------------------------------

TEST(Input, RawDumpEndpointsAreTheFileAndThePeer) {
  std::string out;
  run("cd " + q(captures_dir()) + " && " + bin() + " read serial-raw.bin 2>/dev/null", out);
  EXPECT_NE(out.find(" serial-raw.bin > peer rec 1.0@0 "), std::string::npos) << out;
  EXPECT_EQ(out.find("log > line"), std::string::npos) << out;
}

// --- 12. file-level findings once ---------------------------------------------

TEST(Input, FileFindingsArePrintedOnceNamingTheFileOnce) {
  std::string out;
  // stdout and stderr to one place (a terminal, or 2>&1): once
  run(bin() + " read " + cap_quoted("truncated.pcap") + " 2>&1", out);
  EXPECT_EQ(count(out, "truncated-file"), 1u) << out;
  // stderr alone: the copy names the file once
  for (const char* cmd : {" read ", " stats "}) {
    run(bin() + cmd + cap_quoted("truncated.pcap") + " 2>&1 >/dev/null", out);
    ASSERT_EQ(count(out, "truncated-file"), 1u) << out;
    const std::size_t at = out.find("truncated-file");
    const std::size_t begin =
        out.rfind('\n', at) == std::string::npos ? 0 : out.rfind('\n', at) + 1;
    const std::string line = out.substr(begin, out.find('\n', at) - begin);
    EXPECT_EQ(count(line, "truncated.pcap"), 1u) << line;
  }
}

// --- 17. messages -------------------------------------------------------------

TEST(Input, UnreadableInputMessages) {
  TempDir tmp;
  std::string out;
  EXPECT_EQ(run(bin() + " read " + q(tmp.path) + " 2>&1", out), 2);
  EXPECT_NE(out.find(tmp.path + ": is a directory"), std::string::npos) << out;
  EXPECT_EQ(out.find("read error"), std::string::npos) << out;
  EXPECT_EQ(run(bin() + " read --timeout-ms 0 " + cap_quoted("sll.pcap") + " 2>&1", out), 2);
  EXPECT_NE(out.find("--timeout-ms 0: give a number of milliseconds above 0"), std::string::npos)
      << out;
  EXPECT_LT(out.size(), 300u) << out;
  write_file(tmp.file("four.pcap"), std::string("\xd4\xc3\xb2\xa1", 4));
  EXPECT_EQ(run(bin() + " read " + q(tmp.file("four.pcap")) + " 2>&1", out), 2);
  EXPECT_NE(out.find("four.pcap: offset 0: the pcap file header is cut short (4 of 24 bytes)"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("only got"), std::string::npos) << out;
  EXPECT_EQ(count(out, "four.pcap"), 1u) << out;
}

constexpr std::int64_t T = 1714564800LL * 1000000;
const Ip4 A{10, 1, 0, 1}, B{10, 1, 0, 2};

// The one finding of a broken capture, from --json: the message names the
// record and the offset the structured keys carry.
nlohmann::json capture_finding(const std::string& path, const std::string& code) {
  std::string out;
  run(bin() + " read --json " + q(path) + " 2>/dev/null", out);
  std::stringstream ss(out);
  nlohmann::json found;
  for (std::string l; std::getline(ss, l);) {
    auto j = nlohmann::json::parse(l);
    if (j["type"] == "finding" && j["code"] == code) found = j;
  }
  return found;
}

TEST(Input, BrokenRecordsHaveCodesOfTheirOwnAndOffsetsThatAgree) {
  TempDir tmp;
  const std::string pkt = eth(udp4(A, B, 40000, 5000, top::with_checksum("#TPUG2wPTZ05")));
  {
    // bad caplen: the second record claims 300000 bytes
    PcapWriter w(tmp.file("caplen.pcap"), 1);
    w.write(T, pkt);
    w.write(T + 1, pkt);
  }
  const std::size_t second = 24 + 16 + pkt.size();
  write_file(tmp.file("caplen.pcap"),
             with_u32(slurp(tmp.file("caplen.pcap")), second + 8, 300000));  // its caplen
  auto j = capture_finding(tmp.file("caplen.pcap"), "bad-caplen");
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["record"], 2);
  EXPECT_EQ(j["offset"], second);
  EXPECT_NE(
      j["message"].get<std::string>().find("record 2 at file offset " + std::to_string(second)),
      std::string::npos)
      << j.dump();

  // pcapng: section header (28), interface (20), then packet blocks
  std::vector<NgPacket> pk = {{0, T, pkt}, {0, T + 1, pkt}};
  std::string ng = pcapng({1}, pk);
  const std::size_t first_epb = 28 + 20;
  std::uint32_t epb_len;
  std::memcpy(&epb_len, ng.data() + first_epb + 4, 4);
  const std::size_t second_epb = first_epb + epb_len;
  // the second packet block 7 bytes long, then on interface 9 of 1
  write_file(tmp.file("seven.pcapng"), with_u32(ng, second_epb + 4, 7));
  j = capture_finding(tmp.file("seven.pcapng"), "bad-block-length");
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["record"], 2);
  EXPECT_EQ(j["offset"], second_epb);
  EXPECT_NE(j["message"].get<std::string>().find("record 2 in the block at file offset " +
                                                 std::to_string(second_epb)),
            std::string::npos)
      << j.dump();

  write_file(tmp.file("iface.pcapng"), with_u32(ng, second_epb + 8, 9));
  j = capture_finding(tmp.file("iface.pcapng"), "unknown-interface");
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["record"], 2);
  EXPECT_EQ(j["offset"], second_epb);

  // a truncated pcapng: the offset of the cut block, not 0
  write_file(tmp.file("cut.pcapng"), ng.substr(0, ng.size() - 10));
  j = capture_finding(tmp.file("cut.pcapng"), "truncated-file");
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["record"], 2);
  EXPECT_EQ(j["offset"], second_epb);
}

}  // namespace
}  // namespace topdump::test
