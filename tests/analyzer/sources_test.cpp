// Capture sources: pcap link types written with libpcap, hand-built pcapng
// with several interfaces, truncated files, snap length cuts, and the
// exit status and stats JSON of the real binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>

#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"
#include "test_support.hpp"
#include "top/frame.hpp"

namespace topdump::test {
namespace {

using namespace pcapio;

const Ip4 A{10, 1, 0, 1}, B{10, 1, 0, 2};
const Ip6 A6{0x20, 0x01, 0x0d, 0xb8, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
const Ip6 B6{0x20, 0x01, 0x0d, 0xb8, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2};

struct LinkCase {
  const char* name;
  int dlt;
  std::string (*wrap)(std::string_view);
  std::uint32_t ip_offset;
};

std::string eth_plain(std::string_view ip) { return eth(ip); }
std::string eth_vlan(std::string_view ip) { return eth(ip, {100, 200}); }
std::string raw_ip(std::string_view ip) { return std::string(ip); }

class Links : public ::testing::TestWithParam<LinkCase> {};

TEST_P(Links, Ipv4AndIpv6UdpWithPositions) {
  const LinkCase& c = GetParam();
  TempDir tmp;
  std::string req = top::with_checksum("#tpUG6wGAYEC7832"),
              resp = top::with_checksum("#tpGU6wGAYEC7832");
  {
    PcapWriter w(tmp.file("x.pcap"), c.dlt);
    ASSERT_TRUE(w.ok());
    w.write(T, c.wrap(udp4(A, B, 40000, 5000, req)));
    w.write(T + 5000, c.wrap(udp4(B, A, 5000, 40000, resp)));
    w.write(T + 6000,
            c.wrap(udp6(A6, B6, 40000, 9003,
                        top::with_checksum("#TPPG2wGIA01") + top::with_checksum("#TPPG2wGIA00"))));
  }
  Recorder r = read(tmp.file("x.pcap"));
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.frames[0].from, "10.1.0.1:40000");
  EXPECT_EQ(r.frames[0].to, "10.1.0.2:5000");
  EXPECT_EQ(r.frames[0].pos.record, 1u);
  EXPECT_EQ(r.frames[0].pos.offset, c.ip_offset + 28u);
  EXPECT_EQ(r.frames[1].reply_to, 1u);
  EXPECT_EQ(r.frames[1].latency, 5000);
  EXPECT_EQ(r.frames[2].from, "[2001:db8::1]:40000");
  EXPECT_EQ(r.frames[2].pos.offset, c.ip_offset + 48u);
  EXPECT_EQ(r.frames[3].pos.record, 3u);
  EXPECT_EQ(r.frames[3].pos.index, 1u);
  EXPECT_EQ(r.frames[3].pos.offset, c.ip_offset + 48u + 14u);
  EXPECT_TRUE(r.notes.empty() || !r.has_note(ACode::bad_packet));
}

INSTANTIATE_TEST_SUITE_P(
    Pcap, Links,
    ::testing::Values(LinkCase{"ethernet", 1, eth_plain, 14}, LinkCase{"vlan", 1, eth_vlan, 22},
                      LinkCase{"sll", 113, sll, 16}, LinkCase{"sll2", 276, sll2, 20},
                      LinkCase{"raw", 12, raw_ip, 0}, LinkCase{"ipv4", 228, raw_ip, 0},
                      LinkCase{"null", 0, null_lo, 4}, LinkCase{"loop", 108, loop_lo, 4}),
    [](const ::testing::TestParamInfo<LinkCase>& i) { return std::string(i.param.name); });

TEST(Pcap, ContentRecognitionAndExtraPorts) {
  TempDir tmp;
  {
    PcapWriter w(tmp.file("x.pcap"), 1);
    w.write(T, eth(udp4(A, B, 1111, 2222, top::with_checksum("#TPUG2wPTZ05"))));  // TOP by content
    w.write(T + 1, eth(udp4(A, B, 1111, 3333, "hello, not TOP")));                // skipped
    w.write(T + 2, eth(udp4(A, B, 1111, 4444, "ab#")));  // only with --port
  }
  Recorder r = read(tmp.file("x.pcap"));
  EXPECT_EQ(r.frames.size(), 1u);
  SourceOptions o;
  o.udp_ports.insert(4444);
  Recorder r2 = read(tmp.file("x.pcap"), o);
  EXPECT_EQ(r2.frames.size(), 1u);
  EXPECT_EQ(r2.garbage_codes.size(), 1u);
}

TEST(Pcap, MultiInterfacePcapng) {
  TempDir tmp;
  std::vector<NgPacket> pk = {
      {0, T, eth(udp4(A, B, 40000, 5000, top::with_checksum("#TPUG2wPTZ05")))},
      {1, T + 1000, eth(udp4(B, A, 9003, 9004, top::with_checksum("#TPGP2wGIA01")))},
      {0, T + 2000, eth(udp4(B, A, 5000, 40000, top::with_checksum("#TPGU2wPTZ05")))},
  };
  write_file(tmp.file("x.pcapng"), pcapng({1, 1}, pk));
  Recorder r = read(tmp.file("x.pcapng"));
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.frames[1].pos.record, 2u);
  EXPECT_EQ(r.frames[1].ts, T + 1000);
  EXPECT_EQ(r.frames[2].reply_to, 1u);
}

TEST(Pcap, TruncatedFileKeepsEarlierRecords) {
  TempDir tmp;
  {
    PcapWriter w(tmp.file("x.pcap"), 1);
    for (int i = 0; i < 3; ++i)
      w.write(T + i, eth(udp4(A, B, 40000, 5000, top::with_checksum("#TPUG2wPTZ05"))));
  }
  std::string all = slurp(tmp.file("x.pcap"));
  write_file(tmp.file("x.pcap"), all.substr(0, all.size() - 10));
  Recorder r = read(tmp.file("x.pcap"));
  EXPECT_EQ(r.frames.size(), 2u);
  ASSERT_TRUE(r.has_note(ACode::truncated_file));
  for (const auto& n : r.notes)
    if (n.note.code == ACode::truncated_file) {
      EXPECT_EQ(n.pos.record, 3u);
      EXPECT_EQ(n.note.severity, top::Severity::error);
    }
}

TEST(Pcap, SnapLengthCutIsAFindingAndTheRestIsDecoded) {
  TempDir tmp;
  std::string p = eth(udp4(A, B, 40000, 5000, top::with_checksum("#tpUG6wGAYEC7832")));
  {
    PcapWriter w(tmp.file("x.pcap"), 1);
    w.write(T, p, 50);
    w.write(T + 1, eth(udp4(A, B, 40000, 5000, top::with_checksum("#TPUG2wPTZ05"))));
  }
  Recorder r = read(tmp.file("x.pcap"));
  EXPECT_TRUE(r.has_note(ACode::snaplen_cut));
  ASSERT_FALSE(r.garbage_codes.empty());
  EXPECT_NE(std::find(r.garbage_codes.begin(), r.garbage_codes.end(), "truncated"),
            r.garbage_codes.end());
  EXPECT_EQ(r.garbage_pos[0].record, 1u);
  ASSERT_EQ(r.frames.size(), 1u);
}

TEST(Pcap, MalformedHeadersAreFindingsNotCrashes) {
  TempDir tmp;
  {
    PcapWriter w(tmp.file("x.pcap"), 1);
    std::string ip = udp4(A, B, 40000, 5000, top::with_checksum("#TPUG2wPTZ05"));
    w.write(T, eth(ip).substr(0, 20));  // IP cut short
    std::string bad = eth(ip);
    bad[14] = 0x41;  // IHL 4
    w.write(T + 1, bad);
    w.write(T + 2, std::string(5, '\0'));  // not even Ethernet
    w.write(T + 3, eth(ip));
  }
  Recorder r = read(tmp.file("x.pcap"));
  EXPECT_EQ(r.count_note(ACode::bad_packet), 3u);
  EXPECT_EQ(r.frames.size(), 1u);
}
// The port tables the dissector looks each packet up in (a 64-bit filter on
// a port's low six bits, then the ports): a port that shares a filter bit
// with one in the set is not in it, and a set too large for the inline
// ports is searched whole.
TEST(Pcap, PortTableHoldsExactlyItsPorts) {
  const PortTable none(std::set<std::uint16_t>{});
  const PortTable few(std::set<std::uint16_t>{5000, 9003, 9004});
  for (std::uint32_t p = 0; p < 65536; ++p) {
    const auto port = static_cast<std::uint16_t>(p);
    EXPECT_FALSE(none[port]) << p;
    EXPECT_EQ(few[port], p == 5000 || p == 9003 || p == 9004) << p;
  }
  std::set<std::uint16_t> ports;
  for (std::uint16_t p = 1; p <= 40; ++p) ports.insert(static_cast<std::uint16_t>(p * 1000));
  ports.insert(65535);
  const PortTable many(ports);
  for (std::uint32_t p = 0; p < 65536; ++p)
    EXPECT_EQ(many[static_cast<std::uint16_t>(p)], ports.count(static_cast<std::uint16_t>(p)) == 1)
        << p;
}

// A bridged or mirrored link records a packet twice: the same IPv4
// identification, addresses, ports and payload. The copy is skipped with an
// info note; without that it was a second request (the first then
// unanswered) or an unsolicited reply (an outside judge's capture with 3%
// duplicates: 54 unanswered, 60 unsolicited). The same bytes under another
// identification are a new datagram, and identification 0 (set by no
// sender that numbers its datagrams) is not judged.
TEST(Pcap, ADatagramRecordedTwiceIsSkipped) {
  TempDir tmp;
  const std::string req = top::with_checksum("#TPUG2wPTZ05");
  const std::string rep = top::with_checksum("#TPGU2wPTZ05");
  auto up = [&](std::uint16_t id) { return eth(udp4(A, B, 40000, 5000, req, {.id = id})); };
  auto down = [&](std::uint16_t id) { return eth(udp4(B, A, 5000, 40000, rep, {.id = id})); };
  {
    PcapWriter w(tmp.file("x.pcap"), 1);
    w.write(T, up(7));
    w.write(T + 300, up(7));  // the same packet again
    w.write(T + 5000, down(9));
    w.write(T + 5400, down(9));
    w.write(T + 100000, up(8));  // a new request with the same bytes
    w.write(T + 104000, down(10));
    w.write(T + 200000, up(0));
    w.write(T + 200300, up(0));  // no identification: two requests
    w.write(T + 204000, down(0));
    w.write(T + 204100, down(0));
  }
  Recorder r = read(tmp.file("x.pcap"));
  EXPECT_EQ(r.count_note(ACode::duplicate_datagram), 2u);
  ASSERT_EQ(r.frames.size(), 8u);
  for (const auto& f : r.frames) EXPECT_FALSE(has_code(f, "unsolicited")) << f.n;
  EXPECT_FALSE(r.has_note(ACode::unanswered));
  EXPECT_EQ(r.frames[1].reply_to, 1u);
  EXPECT_EQ(r.frames[3].reply_to, 3u);
}

// --- serial logs -------------------------------------------------------------

TEST(Time, ParseAndFormat) {
  EXPECT_EQ(parse_time("2024-05-01T12:00:00Z"), T);
  EXPECT_EQ(parse_time("2024-05-01T14:00:00.25+02:00"), T + 250000);
  EXPECT_EQ(parse_time("1714564800.000001"), T + 1);
  EXPECT_FALSE(parse_time("yesterday"));
  EXPECT_EQ(format_time(T + 1), "2024-05-01T12:00:00.000001Z");
}

// format_time's calendar arithmetic against its slow twin, gmtime_r and
// printf, over dates either side of the epoch, leap days, year ends and
// microseconds.
TEST(Time, FormatMatchesGmtime) {
  auto slow = [](std::int64_t us) {
    std::int64_t sec = us / 1000000, frac = us % 1000000;
    if (frac < 0) frac += 1000000, --sec;
    const auto t = static_cast<std::time_t>(sec);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char b[64];
    std::snprintf(b, sizeof b, "%04d-%02d-%02dT%02d:%02d:%02d.%06lldZ", tm.tm_year + 1900,
                  tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec,
                  static_cast<long long>(frac));
    return std::string(b);
  };
  std::vector<std::int64_t> at = {0,
                                  -1,
                                  1,
                                  951782400000000,     // 2000-02-29
                                  951868799999999,     // 2000-02-29T23:59:59.999999
                                  4107542399999999,    // 2100-02-28T23:59:59.999999
                                  253402300799999999,  // 9999-12-31T23:59:59.999999
                                  -62135596800000000,  // 0001-01-01
                                  -2208988800000001};  // 1899-12-31T23:59:59.999999
  std::uint64_t x = 88172645463325252ULL;              // xorshift: dates from 0001 to 9999
  for (int i = 0; i < 20000; ++i) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    at.push_back(-62135596800000000 + static_cast<std::int64_t>(x % 315537897600000000ULL));
  }
  for (std::int64_t us : at) ASSERT_EQ(format_time(us), slow(us)) << us;
}

// --- the binary: exit status, stats JSON -----------------------------------------

TEST(Binary, ExitStatus) {
  std::string out, bin = topdump_bin(), caps = captures_dir();
  EXPECT_EQ(run("'" + bin + "' read '" + caps + "/sll.pcap' 2>/dev/null", out), 0);
  EXPECT_EQ(run("'" + bin + "' read '" + caps + "/sample.pcap' 2>/dev/null", out), 1);
  EXPECT_EQ(run("'" + bin + "' read /nonexistent.pcap 2>/dev/null", out), 2);
  EXPECT_EQ(run("'" + bin + "' read --bogus x 2>/dev/null", out), 2);
  EXPECT_EQ(run("'" + bin + "' read --csv n,nope '" + caps + "/sll.pcap' 2>/dev/null", out), 2);
  EXPECT_EQ(run("'" + bin + "' read --from yesterday '" + caps + "/sll.pcap' 2>/dev/null", out), 2);
  EXPECT_EQ(run("'" + bin + "' 2>/dev/null", out), 2);
  EXPECT_EQ(run("'" + bin + "' stats '" + caps + "/sll.pcap' /nonexistent 2>/dev/null", out), 2);
}

// With --format pcap the file is opened by topdump (a larger read buffer
// for libpcap): a missing file and a file that is no capture are exit 2
// with the file named, and a capture reads as with detection.
TEST(Binary, ForcedPcapFormatOpensAndNamesTheFile) {
  TempDir tmp;
  std::string out;
  const std::string bin = topdump_bin();
  EXPECT_EQ(run("'" + bin + "' read --format pcap /nonexistent.pcap 2>&1", out), 2);
  EXPECT_NE(out.find("/nonexistent.pcap: cannot open"), std::string::npos) << out;
  {
    std::ofstream junk(tmp.file("junk.pcap"));
    junk << "not a capture at all";
  }
  EXPECT_EQ(run("'" + bin + "' stats --format pcap '" + tmp.file("junk.pcap") + "' 2>&1", out), 2);
  EXPECT_NE(out.find(tmp.file("junk.pcap") + ": "), std::string::npos) << out;
  std::string forced, detected;
  EXPECT_EQ(run("'" + bin + "' read --format pcap '" + captures_dir() + "/sll.pcap'", forced), 0);
  EXPECT_EQ(run("'" + bin + "' read '" + captures_dir() + "/sll.pcap'", detected), 0);
  EXPECT_FALSE(forced.empty());
  EXPECT_EQ(forced, detected);
}

TEST(Binary, StatsJsonHasIntegerCounts) {
  std::string out;
  ASSERT_EQ(run("'" + topdump_bin() + "' stats --json '" + captures_dir() + "/sample.pcap' '" +
                    captures_dir() + "/sll.pcap' 2>/dev/null",
                out),
            1);
  auto j = nlohmann::json::parse(out);
  ASSERT_TRUE(j["frames"].is_number_integer());
  ASSERT_TRUE(j["bad_checksum"].is_number_integer());
  EXPECT_EQ(j["frames"].get<int>(), 35);
  EXPECT_EQ(j["bad_checksum"].get<int>(), 1);
  EXPECT_EQ(j["per_ident"]["GAY"].get<int>(), 9);
  // Two: the copies of the PTZ request the device answered are not
  // unanswered (field fidelity), the GAY with a bad checksum says why.
  EXPECT_EQ(j["pairing"]["unanswered"].get<int>(), 2);
}

TEST(Binary, FiltersSelectFrames) {
  std::string out, caps = captures_dir();
  run("'" + topdump_bin() + "' read --json --ident GAY --addr G '" + caps +
          "/sample.pcap' 2>/dev/null",
      out);
  std::istringstream in(out);
  std::string line;
  int frames = 0;
  while (std::getline(in, line)) {
    auto j = nlohmann::json::parse(line);
    if (j["type"] == "frame") {
      EXPECT_EQ(j["ident"], "GAY");
      ++frames;
    }
  }
  EXPECT_EQ(frames, 7);
  run("'" + topdump_bin() + "' read --csv ident --severity error '" + caps +
          "/sample.pcap' 2>/dev/null",
      out);
  EXPECT_EQ(out, "ident\nGAY\n");
  run("'" + topdump_bin() +
          "' read --csv n --addr 192.168.144.108:5000 --from 1714564800.3 --to 1714564800.305 '" +
          caps + "/sample.pcap' 2>/dev/null",
      out);
  EXPECT_EQ(out, "n\n7\n8\n9\n");
}

}  // namespace
}  // namespace topdump::test

namespace topdump::test {
namespace {

// CI smoke test of the bench generator at a tiny size.
TEST(BenchGenerator, SmallCaptureHasTheAdvertisedMix) {
  TempDir tmp;
  const std::string capture = generated_capture(tmp, "b.pcap", 3000, 5);
  ASSERT_FALSE(capture.empty());
  std::string out;
  ASSERT_EQ(run("'" + topdump_bin() + "' stats --json '" + capture + "' 2>/dev/null", out), 1);
  auto j = nlohmann::json::parse(out);
  auto frames = j["frames"].get<std::int64_t>();
  EXPECT_GE(frames, 3000);
  EXPECT_LE(frames, 3003);
  double bad =
      static_cast<double>(j["bad_checksum"].get<std::int64_t>()) / static_cast<double>(frames);
  EXPECT_GT(bad, 0.01);
  EXPECT_LT(bad, 0.06);
  EXPECT_GT(j["pairing"]["paired"].get<std::int64_t>(), frames / 5);
  EXPECT_LT(j["records"].get<std::int64_t>(), frames);  // some datagrams carry several frames
  // Every reply comes 1-20 ms after its request; 2% of requests are never
  // answered (and 5% of datagrams add a PTZ request nobody answers). Pairing
  // must not hand a reply to one of those: p95 within the generator's 20 ms.
  ASSERT_GE(j["latency"].size(), 6u);
  for (const auto& [ident, l] : j["latency"].items()) {
    EXPECT_LE(l["p95_ms"].get<double>(), 20.0) << ident;
    EXPECT_GE(l["min_ms"].get<double>(), 1.0) << ident;
  }
}

// The generator's TCP mode (the C10/C20 TCP port, some payloads split in
// two segments) and serial mode (a raw dump of both directions) carry the
// same traffic: the TCP capture reassembles to every frame and pairs as the
// UDP one does; the serial dump decodes to every frame, with no garbage.
TEST(BenchGenerator, TcpAndSerialModesCarryTheSameFrames) {
  TempDir tmp;
  const std::string tcp = generated_capture(tmp, "t.pcap", 3000, 5, "tcp");
  const std::string raw = generated_capture(tmp, "s.bin", 3000, 5, "serial");
  ASSERT_FALSE(tcp.empty());
  ASSERT_FALSE(raw.empty());
  std::string out;
  ASSERT_EQ(run("'" + topdump_bin() + "' stats --json '" + tcp + "' 2>/dev/null", out), 1);
  auto j = nlohmann::json::parse(out);
  const auto frames = j["frames"].get<std::int64_t>();
  EXPECT_GE(frames, 3000);
  EXPECT_LE(frames, 3003);
  EXPECT_GT(j["records"].get<std::int64_t>(), frames);  // some payloads in two segments
  EXPECT_GT(j["pairing"]["paired"].get<std::int64_t>(), frames / 5);
  EXPECT_EQ(j["garbage"].get<std::int64_t>(), 0);
  for (const auto& c : j["conversations"]) EXPECT_EQ(c["transport"], "tcp");
  ASSERT_EQ(run("'" + topdump_bin() + "' stats --json --format raw '" + raw + "' 2>/dev/null", out),
            1);
  j = nlohmann::json::parse(out);
  EXPECT_EQ(j["frames"].get<std::int64_t>(), frames);
  EXPECT_EQ(j["garbage"].get<std::int64_t>(), 0);
}

}  // namespace
}  // namespace topdump::test

namespace topdump::test {
namespace {

// A list option takes one value per occurrence: it never swallows the files.
TEST(Binary, ListOptionsDoNotSwallowFiles) {
  std::string out, caps = captures_dir();
  ASSERT_EQ(run("'" + topdump_bin() + "' stats --json --ident GAY --port 6000 '" + caps +
                    "/sll.pcap' '" + caps + "/sll2.pcap' 2>/dev/null",
                out),
            0);
  auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["frames"].get<int>(), 2);
  EXPECT_EQ(j["records"].get<int>(), 4);
}

}  // namespace
}  // namespace topdump::test

namespace topdump {
namespace {

// pcapio: one IPv4 checksum (RFC 1071 example header), one Endpoint.
TEST(Pcapio, Ipv4ChecksumAndEndpoints) {
  const std::string h(
      "\x45\x00\x00\x73\x00\x00\x40\x00\x40\x11\x00\x00\xc0\xa8\x00\x01\xc0\xa8\x00\xc7", 20);
  EXPECT_EQ(pcapio::ip_checksum(h), 0xB861);
  const std::string ip = pcapio::udp4({10, 0, 0, 1}, {10, 0, 0, 2}, 1, 2, "x", {7, true});
  EXPECT_EQ(pcapio::ip_checksum(std::string_view(ip).substr(0, 20)),
            0);                                       // a valid header sums to 0
  EXPECT_EQ(static_cast<std::uint8_t>(ip[5]), 7);     // id
  EXPECT_EQ(static_cast<std::uint8_t>(ip[6]), 0x40);  // DF
  const auto e = pcapio::Endpoint::ipv4(0x7F000001u, 5000);
  EXPECT_EQ(e.text(), "127.0.0.1:5000");
  EXPECT_EQ(e.ipv4(), 0x7F000001u);
  EXPECT_EQ(e, pcapio::Endpoint::ipv4(0x7F000001u, 5000));
  pcapio::Endpoint named;
  named.name = "tty\r";
  EXPECT_EQ(named.text(), "tty\\r");
}

// The recorder of topsim and topconf writes through the same builder: the
// packets read back with their endpoints and payloads.
TEST(Pcapio, RecorderWritesWhatTopdumpReads) {
  test::TempDir tmp;
  const std::string path = tmp.file("r.pcap");
  {
    pcapio::Recorder r(path, false);
    r.write(pcapio::Endpoint::ipv4(0x7F000001u, 40000), pcapio::Endpoint::ipv4(0x7F000001u, 5000),
            top::with_checksum("#TPUG2wPTZ05"));
    r.write(pcapio::Endpoint::ipv4(0x7F000001u, 5000), pcapio::Endpoint::ipv4(0x7F000001u, 40000),
            top::with_checksum("#TPGU2wPTZ05"));
    EXPECT_EQ(r.packets(), 2u);
  }
  EXPECT_THROW(pcapio::Recorder(tmp.file("no/such/dir.pcap"), false), std::runtime_error);
  test::Recorder rec;
  Analyzer a(AnalyzerOptions{}, rec);
  std::string err;
  ASSERT_TRUE(read_file(path, Format::automatic, a, SourceOptions{}, err)) << err;
  a.finish();
  ASSERT_EQ(rec.frames.size(), 2u);
  EXPECT_EQ(rec.frames[0].from, "127.0.0.1:40000");
  EXPECT_EQ(rec.frames[1].reply_to, 1u);
}

}  // namespace
}  // namespace topdump
