// The real Topotek camera's sessions (captures/sip-bench, PixEagle bench
// evidence): every session is healthy by its own evidence, and topdump must
// read it so. Each query is paired (but for the drops the sessions do
// show), the device's copies are copies, nothing above info is said but the
// bench client's own U source, and the exit status is 0 where the evidence
// shows no problem. The same camera made silent, or made to drop a query,
// by editing a real session, is still said to be so.
#include <gtest/gtest.h>
#include <pcap/pcap.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include "test_support.hpp"

namespace topdump::test {
namespace {

std::string bench_dir() { return captures_dir() + "/sip-bench"; }

std::vector<std::string> sessions() {
  std::vector<std::string> v;
  for (const auto& e : std::filesystem::directory_iterator(bench_dir()))
    if (e.path().extension() == ".pcap") v.push_back(e.path().stem().string());
  std::sort(v.begin(), v.end());
  return v;
}

// The reads the camera really left unanswered, by frame number: no
// datagram came back on any port (captures/sip-bench/README.md).
const std::map<std::string, std::set<std::uint64_t>>& drops() {
  static const std::map<std::string, std::set<std::uint64_t>> k = {
      {"20260917T072435Z-queries", {5, 6}},
      {"20260917T071854Z-ai-observe", {211}},
      {"20260918T060610Z-rotated-point", {38}},
      // 410: the bench stopped listening 100 ms after it, then recorded its
      // cleanup writes (a limit of the recording: README.md)
      {"20260918T185503Z-qt-point", {262, 410}},
  };
  return k;
}

bool from_camera(const Recorder::F& f) { return f.from.rfind("192.168.0.108:", 0) == 0; }

class SipBench : public ::testing::TestWithParam<std::string> {};

TEST_P(SipBench, IsReadAsTheEvidenceShowsIt) {
  const std::string session = GetParam();
  const std::string path = bench_dir() + "/" + session + ".pcap";
  const Recorder r = read(path);
  ASSERT_FALSE(r.frames.empty());
  const auto d = drops().find(session);
  const std::set<std::uint64_t> dropped =
      d == drops().end() ? std::set<std::uint64_t>{} : d->second;

  std::set<std::uint64_t> answered;
  bool u_source = false;
  std::uint64_t copies = 0;
  for (const auto& f : r.frames) {
    if (f.reply_to) answered.insert(f.reply_to);
    // no frame or session finding above info on a frame
    for (const auto& c : f.codes)
      EXPECT_TRUE(c == "repeated" || c == "tp-length" || c == "length-mismatch")
          << session << " frame " << f.n << " " << top::escape(f.raw) << ": " << c;
    if (from_camera(f)) {
      if (f.copy_of) {
        ++copies;
        ASSERT_LT(f.copy_of, f.n) << session;
        EXPECT_EQ(r.frames.at(f.copy_of - 1).raw, f.raw) << session << " frame " << f.n;
      }
    } else {
      u_source |= f.raw.size() > 4 && f.raw[3] == 'U';
    }
  }
  // every query the bench sent is answered, but for the true drops
  for (const auto& f : r.frames) {
    if (from_camera(f) || f.control != 'r') continue;
    if (dropped.count(f.n))
      EXPECT_FALSE(answered.count(f.n)) << session << " frame " << f.n;
    else
      EXPECT_TRUE(answered.count(f.n)) << session << " query " << f.n << " " << top::escape(f.raw);
  }
  // the camera fans out every reply: copies, noted once with the reply port
  EXPECT_GT(copies, 0u) << session;
  EXPECT_EQ(r.count_note(ACode::fan_out), 1u) << session;
  EXPECT_EQ(r.count_note(ACode::reply_port), 1u) << session;
  // nothing above info but the client's U source and the true drops
  std::set<std::uint64_t> unanswered;
  for (const auto& n : r.notes) {
    if (n.note.severity == top::Severity::info) continue;
    if (n.note.code == ACode::unanswered) {
      unanswered.insert(n.note.frame);
      continue;
    }
    EXPECT_EQ(n.note.code, acode_of(top::Diagnosis::reply_interface))
        << session << ": " << to_string(n.note.code) << " " << n.note.message;
  }
  EXPECT_EQ(unanswered, dropped) << session;
  EXPECT_EQ(r.has_note(acode_of(top::Diagnosis::reply_interface)), u_source) << session;

  // the real binary: exit 0 where the evidence shows no problem, 1 for the
  // client's U source (a warning diagnosis)
  std::string out;
  const int rc = run("'" + topdump_bin() + "' stats '" + path + "' >/dev/null 2>&1", out);
  EXPECT_EQ(rc, u_source ? 1 : 0) << session;
}

INSTANTIATE_TEST_SUITE_P(Sessions, SipBench, ::testing::ValuesIn(sessions()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n;
                           for (char ch : i.param)
                             n += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
                           return n;
                         });

// A real session with some of its packets left out: `keep` sees each
// packet's bytes (raw IPv4) and its index, and says whether it stays.
std::string edited(const TempDir& tmp, const std::string& session,
                   const std::function<bool(std::string_view, int)>& keep) {
  char err[PCAP_ERRBUF_SIZE];
  pcap_t* in = pcap_open_offline((bench_dir() + "/" + session + ".pcap").c_str(), err);
  EXPECT_NE(in, nullptr) << err;
  if (!in) return {};
  const std::string out = tmp.file(session + "-edited.pcap");
  pcap_dumper_t* dump = pcap_dump_open(in, out.c_str());
  EXPECT_NE(dump, nullptr) << pcap_geterr(in);
  pcap_pkthdr* h = nullptr;
  const u_char* data = nullptr;
  for (int i = 0; pcap_next_ex(in, &h, &data) == 1; ++i)
    if (keep(std::string_view(reinterpret_cast<const char*>(data), h->caplen), i))
      pcap_dump(reinterpret_cast<u_char*>(dump), h, data);
  pcap_dump_close(dump);
  pcap_close(in);
  return out;
}

// the camera's address in a raw IPv4 packet's source
bool camera_sent(std::string_view ip) {
  return ip.size() > 16 && static_cast<unsigned char>(ip[12]) == 192 &&
         static_cast<unsigned char>(ip[15]) == 108;
}
std::string_view payload(std::string_view ip) { return ip.substr(28); }

TEST(SipBenchEdited, ACameraMadeSilentIsSilentDevice) {
  // 20260917T045437Z-pan with every datagram of the camera after its
  // fourth left out: the polling goes on, unanswered.
  TempDir tmp;
  int camera = 0;
  const std::string path = edited(tmp, "20260917T045437Z-pan", [&](std::string_view ip, int) {
    return !camera_sent(ip) || ++camera <= 4;
  });
  const Recorder r = read(path);
  ASSERT_EQ(r.count_note(acode_of(top::Diagnosis::silent_device)), 1u);
  std::string out;
  EXPECT_EQ(run("'" + topdump_bin() + "' stats '" + path + "' >/dev/null 2>&1", out), 1);
}

TEST(SipBenchEdited, AQueryWhoseRepliesAreAllLostIsUnanswered) {
  // 20260917T044930Z-queries without the three deliveries of the reply to
  // the GIC read of 04:49:36.646755 (#tpGPCrGIAFEF9FFFEFFFE5C).
  TempDir tmp;
  const std::string lost = "#tpGPCrGIAFEF9FFFEFFFE5C";
  int left_out = 0;
  const std::string path = edited(tmp, "20260917T044930Z-queries", [&](std::string_view ip, int) {
    const bool drop = camera_sent(ip) && payload(ip) == lost;
    left_out += drop;
    return !drop;
  });
  ASSERT_EQ(left_out, 2);  // to 8080 and to 9004
  const Recorder r = read(path);
  ASSERT_EQ(r.count_note(ACode::unanswered), 1u);
  const NoteEvent* n = nullptr;
  for (const auto& x : r.notes)
    if (x.note.code == ACode::unanswered) n = &x;
  const auto& req = r.frames.at(n->note.frame - 1);
  EXPECT_EQ(req.raw, "#TPPG2rGIC0035");
  EXPECT_EQ(req.from, "192.168.0.167:9004");
  EXPECT_EQ(n->note.severity, top::Severity::warning);
  // the other eight queries are still paired
  std::uint64_t paired = 0;
  for (const auto& f : r.frames) paired += f.reply_to != 0;
  EXPECT_EQ(paired, 8u);
}

}  // namespace
}  // namespace topdump::test

namespace topdump::test {
namespace {

std::string bench_to_pcap() { return std::string(TOPKIT_BINARY_DIR) + "/analyzer/bench_to_pcap"; }

// A session log in the bench's format (our own lines, made up): the start
// names the camera, the binds the bench's ports, then a read, its reply to
// two ports, a cleanup send (no port in the log: the first bound one).
const char* kLog =
    R"({"utc": "2026-09-17T04:49:30.639391+00:00", "kind": "start", "host": "192.168.0.108"}
{"utc": "2026-09-17T04:49:30.639493+00:00", "kind": "bind", "port": 8080}
{"utc": "2026-09-17T04:49:30.639517+00:00", "kind": "bind", "port": 9004}
{"utc": "2026-09-17T04:49:32.641749+00:00", "kind": "tx", "local_port": 9004, "hex": "2354505044327254524330303438"}
{"utc": "2026-09-17T04:49:32.643626+00:00", "kind": "rx", "local_port": 9004, "peer": ["192.168.0.108", 38909], "hex": "2354504450327254524330303438", "checksum_valid": true}
{"utc": "2026-09-17T04:49:32.643665+00:00", "kind": "rx", "local_port": 8080, "peer": ["192.168.0.108", 38909], "hex": "2354504450327254524330303438", "checksum_valid": true}
{"utc": "2026-09-17T04:49:33.000000+00:00", "kind": "summary", "received": {"192.168.0.108:38909->9004": 1, "192.168.0.108:38909->8080": 1}}
{"utc": "2026-09-17T04:49:33.100000+00:00", "kind": "cleanup_tx", "hex": "2354505047327750545a30303635"}
)";

TEST(BenchToPcap, TranscribesTheLogAsRecorded) {
  TempDir tmp;
  const std::string log = tmp.file("events.jsonl"), pcap = tmp.file("s.pcap");
  { std::ofstream(log) << kLog; }
  std::string out;
  ASSERT_EQ(run("'" + bench_to_pcap() + "' '" + log + "' '" + pcap + "' 2>&1", out), 0) << out;
  EXPECT_NE(out.find("1 tx, 1 cleanup tx, 2 rx (camera 192.168.0.108)"), std::string::npos) << out;
  const Recorder r = read(pcap);
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.frames[0].from, "192.168.0.167:9004");
  EXPECT_EQ(r.frames[0].to, "192.168.0.108:9003");
  EXPECT_EQ(r.frames[0].ts, 1789620572641749);
  EXPECT_EQ(r.frames[1].from, "192.168.0.108:38909");
  EXPECT_EQ(r.frames[1].reply_to, 1u);
  EXPECT_EQ(r.frames[2].to, "192.168.0.167:8080");
  EXPECT_EQ(r.frames[2].copy_of, 2u);
  EXPECT_EQ(r.frames[3].from, "192.168.0.167:8080");  // the cleanup: the first bound port
  EXPECT_EQ(r.frames[3].raw, "#TPPG2wPTZ0065");
  // --host names the bench's address
  ASSERT_EQ(run("'" + bench_to_pcap() + "' --host 10.1.2.3 '" + log + "' '" + pcap + "' 2>&1", out),
            0);
  EXPECT_EQ(read(pcap).frames[0].from, "10.1.2.3:9004");
}

TEST(BenchToPcap, ABadLogIsAnErrorNamingTheFileAndLine) {
  TempDir tmp;
  const std::string log = tmp.file("events.jsonl"), pcap = tmp.file("s.pcap");
  std::string out;
  // a line that is no JSON: exit 2, the line named, no pcap left behind
  { std::ofstream(log) << std::string(kLog).substr(0, 200) << "\n{\"utc\": oops\n"; }
  EXPECT_EQ(run("'" + bench_to_pcap() + "' '" + log + "' '" + pcap + "' 2>&1", out), 2);
  EXPECT_NE(out.find("events.jsonl:3: not a JSON object"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(pcap));
  // received datagrams that do not add up to the summary
  std::string lying = kLog;
  lying.replace(lying.find("\"192.168.0.108:38909->8080\": 1"), 30,
                "\"192.168.0.108:38909->8080\": 2");
  { std::ofstream(log) << lying; }
  EXPECT_EQ(run("'" + bench_to_pcap() + "' '" + log + "' '" + pcap + "' 2>&1", out), 2);
  EXPECT_NE(out.find("do not add up to the summary"), std::string::npos) << out;
  // a missing file, a bad --host, a full disk
  EXPECT_EQ(run("'" + bench_to_pcap() + "' '" + tmp.file("none") + "' '" + pcap + "' 2>&1", out),
            2);
  EXPECT_NE(out.find("cannot open"), std::string::npos) << out;
  { std::ofstream(log) << kLog; }
  EXPECT_EQ(
      run("'" + bench_to_pcap() + "' --host 300.1.1.1 '" + log + "' '" + pcap + "' 2>&1", out), 2);
  EXPECT_EQ(run("'" + bench_to_pcap() + "' '" + log + "' /dev/full 2>&1", out), 2) << out;
  // and the device is still there (a failed run removes only a file of its own)
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/full"));
}

}  // namespace
}  // namespace topdump::test
