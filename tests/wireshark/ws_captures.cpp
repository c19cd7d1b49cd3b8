// Writes the captures tests/wireshark compares tshark (with the generated
// top.lua) and topdump on, into the directory given:
//   forms.pcap           every form of every catalog command, built with
//                        top::build_frame and top::example_data, one per UDP
//                        datagram (SkyDroid on 5000, Topotek 9004 -> 9003)
//   forms.fields         per frame of forms.pcap: the identifier and the
//                        fields its form has (what tshark must show)
//   forms-skydroid.pcap  the SkyDroid frames of forms.pcap alone
//   forms-user0.pcap     the same frames as a serial dump: DLT_USER0, one
//                        frame per record (as `topdump -w` or topsim would
//                        write the serial line; topdump does not read it, so
//                        it is compared with forms-skydroid.pcap)
//   vectors.pcap         every frame of tests/vectors/*.json, one datagram
//                        each, on its dialect's port (lying lengths, header
//                        case errata, TMP, lowercase hex, CR/LF, ...)
//   tcp.pcap             TCP 5000: a frame that fails its checksum before a frame
//                        split over two segments; CR/LF in the next segment
//   heuristic.pcap       TOP on ports nobody registered (UDP 40001/40002, TCP
//                        40003/40004 with a frame split over two segments and
//                        two frames in one datagram)
//   c12-push.pcap        a real C12's attitude pushes, client first
//                        (#tpUGCrGAC, docs/FIELD.md), in three conversations
//                        whose device end the dissector must learn as topdump
//                        does: from the device port (40000 -> 5000), from the
//                        GAA write (UDP 5000 -> 5000, the vendor's app), from
//                        the push's layout alone (UDP 40005/40006, nothing
//                        asked first)
//   sip-bench.pcap       frames of a real Topotek camera none of the two
//                        documents lists, byte for byte with their times and
//                        ports as PixEagle's bench recorded them (FED, the
//                        ODR detections, ODZ, OFT status 3), and
//   sip-bench.fields     the fields tshark must show for each
#include <pcap/pcap.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"
#include "top/top.hpp"

namespace {

using pcapio::Ip4;
using pcapio::PcapWriter;
namespace w = pcapio;

constexpr Ip4 kClient{192, 168, 144, 10};
constexpr Ip4 kDevice{192, 168, 144, 108};
constexpr int kDltUser0 = 147;
constexpr std::int64_t kT0 = 1714564800000000;  // 2024-05-01T12:00:00Z

// One TCP connection from the client's port `cp` to the device's `dp`, opened
// by the handshake: segments 10 ms apart, each side's sequence number kept.
struct TcpFlow {
  PcapWriter& out;
  std::int64_t& ts;
  std::uint16_t cp, dp;
  std::uint32_t cs = 1000, ds = 5000;
  TcpFlow(PcapWriter& o, std::int64_t& t, std::uint16_t client_port, std::uint16_t device_port)
      : out(o), ts(t), cp(client_port), dp(device_port) {
    (*this)(true, pcapio::kSyn, "");
    (*this)(false, pcapio::kSyn | pcapio::kAck, "");
    (*this)(true, pcapio::kAck, "");
  }
  void operator()(bool up, std::uint8_t flags, const std::string& payload) {
    const std::uint32_t next =
        static_cast<std::uint32_t>(payload.size()) + ((flags & w::kSyn) ? 1 : 0);
    if (up) {
      out.write(ts, w::eth(w::tcp4(kClient, kDevice, cp, dp, cs, ds, flags, payload)));
      cs += next;
    } else {
      out.write(ts, w::eth(w::tcp4(kDevice, kClient, dp, cp, ds, cs, flags, payload)));
      ds += next;
    }
    ts += 10000;
  }
};

// The bytes of a vector: each UTF-8 char is one byte (tests/vectors/README.md).
std::string bytes_of(const std::string& utf8) {
  std::string out;
  for (std::size_t i = 0; i < utf8.size();) {
    auto c = static_cast<unsigned char>(utf8[i]);
    if ((c & 0xE0) == 0xC0 && i + 1 < utf8.size()) {
      out += static_cast<char>(
          (((c & 0x1Fu) << 6) | (static_cast<unsigned char>(utf8[i + 1]) & 0x3Fu)) & 0xFF);
      i += 2;
    } else {
      out += static_cast<char>(c);
      ++i;
    }
  }
  return out;
}

struct Built {
  bool skydroid = false;
  bool from_client = true;
  std::string bytes;
};

int write_forms(const std::string& dir) {
  std::vector<Built> frames;
  std::ofstream fields(dir + "/forms.fields");
  for (top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek}) {
    const char client = d == top::Dialect::skydroid ? 'U' : 'P';
    for (const top::CommandSpec& c : top::commands(d))
      for (const top::FormSpec& f : c.forms) {
        std::string data = top::example_data(f);
        // the form's "no value" data (SDC all zero: no card) shows no field values
        if (!f.none.empty() && data == f.none && !data.empty()) data.back() = '1';
        const bool request = f.role != top::Role::response;
        top::BuildSpec b;
        b.header = top::choose_header(d, c.address, data.size());
        b.src = request ? client : c.address;
        b.dst = request ? c.address : client;
        b.control = f.control;
        b.ident = c.ident;
        b.data = data;
        const std::string built = top::build_frame(b);
        // A field form may take what a loose document form also covers
        // (Topotek LRF: 5 digits, inside the document's 3-7 chars): that
        // example shows the field form, which has a frame of its own.
        const top::ParseResult parsed = top::parse_exact(built);
        if (parsed.status == top::ParseStatus::frame && !f.from_field()) {
          const top::Decoded dec = top::decode(parsed.frame, {.dialect = d});
          if (dec.form != &f && dec.form != nullptr && dec.form->from_field()) continue;
        }
        frames.push_back({d == top::Dialect::skydroid, request, built});
        fields << c.ident;
        for (const top::FieldSpec& s : f.fields) fields << ' ' << s.name;
        // example_data gives a form with records (the Topotek ODR) one
        for (const top::FieldSpec& s : f.record) fields << ' ' << s.name;
        fields << '\n';
      }
  }
  PcapWriter all(dir + "/forms.pcap", DLT_EN10MB), sky(dir + "/forms-skydroid.pcap", DLT_EN10MB),
      user0(dir + "/forms-user0.pcap", kDltUser0);
  if (!all.ok() || !sky.ok() || !user0.ok()) return 2;
  std::int64_t ts = kT0;
  for (const Built& x : frames) {
    const std::uint16_t device = x.skydroid ? 5000 : 9003, client = x.skydroid ? 40000 : 9004;
    const std::string pkt =
        x.from_client ? pcapio::eth(pcapio::udp4(kClient, kDevice, client, device, x.bytes))
                      : pcapio::eth(pcapio::udp4(kDevice, kClient, device, client, x.bytes));
    all.write(ts, pkt);
    if (x.skydroid) {
      sky.write(ts, pkt);
      user0.write(ts, x.bytes);
    }
    ts += 10000;
  }
  return 0;
}

int write_vectors(const std::string& dir, const std::string& source) {
  PcapWriter out(dir + "/vectors.pcap", DLT_EN10MB);
  if (!out.ok()) return 2;
  std::int64_t ts = kT0;
  std::uint16_t client = 41000;
  for (const char* file : {"skydroid", "topotek", "extra"}) {
    std::ifstream in(source + "/tests/vectors/" + file + ".json");
    if (!in) return 2;
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& v : j.at("vectors")) {
      const std::string bytes = bytes_of(v.at("bytes").get<std::string>());
      const std::string dialect = v.value("dialect", "skydroid");
      const std::uint16_t port = dialect == "topotek" ? 9003 : 5000;
      // one conversation per vector: each is judged alone, as topdump frame
      // does; a frame addressed to a client travels from the device (topdump
      // takes the role from the conversation, the dissector from addresses)
      const auto r = top::parse_exact(bytes);
      const bool from_device = r.status == top::ParseStatus::frame &&
                               top::is_client_address(r.frame.dst) &&
                               !top::is_client_address(r.frame.src);
      out.write(ts, from_device
                        ? pcapio::eth(pcapio::udp4(kDevice, kClient, port, client++, bytes))
                        : pcapio::eth(pcapio::udp4(kClient, kDevice, client++, port, bytes)));
      ts += 10000;
    }
  }
  return 0;
}

int write_heuristic(const std::string& dir) {
  PcapWriter out(dir + "/heuristic.pcap", DLT_EN10MB);
  if (!out.ok()) return 2;
  std::int64_t ts = kT0;
  auto udp = [&](bool up, const std::string& payload) {
    out.write(ts, w::eth(up ? w::udp4(kClient, kDevice, 40001, 40002, payload)
                            : w::udp4(kDevice, kClient, 40002, 40001, payload)));
    ts += 10000;
  };
  udp(true, top::with_checksum("#tpUG6wGAYEC7832"));
  udp(false, top::with_checksum("#tpGU6wGAYEC7832"));
  udp(true, top::with_checksum("#TPUG2wPTZ05") + top::with_checksum("#TPUD2rVER00"));
  udp(false, top::with_checksum("#TPGU2wPTZ05") + "\r\n" + top::with_checksum("#tpDU6rVER010502"));
  TcpFlow tcp{out, ts, 40003, 40004};
  const std::string gay = top::with_checksum("#tpUG6wGAYEC7832");
  tcp(true, w::kAck | w::kPsh, gay.substr(0, 12));
  tcp(true, w::kAck | w::kPsh, gay.substr(12));
  tcp(false, w::kAck | w::kPsh,
      top::with_checksum("#tpGU6wGAYEC7832") + top::with_checksum("#TPGU2wPTZ05"));
  tcp(true, w::kAck | w::kPsh, top::with_checksum("#TPUG2wPTZ05") + "\r\n");
  return 0;
}

// TCP 5000 edge cases: a frame that fails its checksum (so it waits for the
// look-ahead that could show another length) followed by a frame cut by the
// segment's end, which makes Wireshark hand the first frame over again; CR/LF
// at the start of the next segment.
int write_tcp(const std::string& dir) {
  PcapWriter out(dir + "/tcp.pcap", DLT_EN10MB);
  if (!out.ok()) return 2;
  std::int64_t ts = kT0;
  TcpFlow tcp{out, ts, 40000, 5000};
  tcp(true, w::kAck | w::kPsh, top::with_checksum("#tpUG6wGAP112F32"));
  std::string bad = top::with_checksum("#tpGU6wGAP112F32");
  bad.back() = bad.back() == '0' ? '1' : '0';  // a wrong checksum
  tcp(false, w::kAck | w::kPsh, bad);
  const std::string gac = top::with_checksum("#TPGUCrGACBF33FE070049");
  tcp(false, w::kAck | w::kPsh, gac.substr(0, 20));
  tcp(false, w::kAck | w::kPsh, gac.substr(20) + top::with_checksum("#TPGU2wPTZ07"));
  const std::string gay = top::with_checksum("#tpGU6wGAY083732");
  tcp(false, w::kAck | w::kPsh, "\r\n" + gay.substr(0, 16));
  tcp(false, w::kAck | w::kPsh, gay.substr(16));
  return 0;
}

// A real C12 pushes attitude as #tpUGCrGAC, client first (docs/FIELD.md,
// the C12's recorded push form): the pushes come from the device, whatever
// their addresses say.
int write_c12_push(const std::string& dir) {
  PcapWriter out(dir + "/c12-push.pcap", DLT_EN10MB);
  if (!out.ok()) return 2;
  constexpr Ip4 kApp{192, 168, 144, 11}, kDevice2{192, 168, 144, 109}, kDevice3{192, 168, 144, 110};
  std::int64_t ts = kT0;
  auto udp = [&](Ip4 from, Ip4 to, std::uint16_t sp, std::uint16_t dp, const std::string& p) {
    out.write(ts, w::eth(w::udp4(from, to, sp, dp, p)));
    ts += 10000;
  };
  const std::string gaa = top::with_checksum("#TPUG2wGAA0A"),
                    echo = top::with_checksum("#TPGU2wGAA0A");
  const std::string pushes[] = {top::with_checksum("#tpUGCrGAC0000FC1800C8"),
                                top::with_checksum("#tpUGCrGAC0064FB5000C8"),
                                top::with_checksum("#tpUGCrGAC00C8FA8800C8")};
  udp(kClient, kDevice, 40000, 5000, gaa);
  udp(kDevice, kClient, 5000, 40000, echo);
  for (const std::string& p : pushes) udp(kDevice, kClient, 5000, 40000, p);
  udp(kApp, kDevice2, 5000, 5000, gaa);
  udp(kDevice2, kApp, 5000, 5000, echo);
  for (const std::string& p : pushes) udp(kDevice2, kApp, 5000, 5000, p);
  for (const std::string& p : pushes) udp(kDevice3, kClient, 40006, 40005, p);
  return 0;
}

// A real Topotek camera (192.168.0.108) and PixEagle's bench (192.168.0.167):
// alireza787b/PixEagle @ 3bea324, docs/reporting/agent-ops/
// codex-modernization/evidence/2026-09-17-gimbal-control-bench/<session>/
// events.jsonl, the first delivery of each (UTC).
int write_sip_bench(const std::string& dir) {
  PcapWriter out(dir + "/sip-bench.pcap", DLT_EN10MB);
  std::ofstream fields(dir + "/sip-bench.fields");
  if (!out.ok() || !fields) return 2;
  constexpr Ip4 kBench{192, 168, 0, 167}, kCamera{192, 168, 0, 108};
  struct Real {
    std::int64_t ts;  // microseconds since the epoch
    bool from_camera;
    std::uint16_t camera_port, bench_port;
    const char* hex;
    const char* fields;
  };
  const Real frames[] = {
      // 20260917T050955Z-zoom 05:09:57.284912, 14 ms after #TPPM2wZMC0259
      {1789621797284912, true, 35496, 9004, "237470445041774f445a000000000000000000003430",
       "ODZ data"},
      // 20260917T051606Z-point 05:16:08.998653, status '3' (lost)
      {1789622168998653, true, 59598, 8080, "237470445039774f4654a703230223001600333646",
       "OFT x y width height status"},
      // 20260917T071854Z-ai-observe 07:18:56.503172, 07:18:56.928933, 07:19:03.716098
      {1789629536503172, false, 9003, 8080, "2354505044327746454431303334", "FED output"},
      {1789629536928933, true, 50076, 8080, "23745044500d774f44520115060500650102047f0000004630",
       "ODR count x y width height label confidence"},
      {1789629543716098, false, 9003, 8080, "2354505044327746454432303335", "FED output"},
      // 20260917T072135Z-ai-select 07:21:37.929076
      {1789629697929076, true, 50076, 8080, "23745044500d774f445201090005006e0727047f0000003132",
       "ODR count x y width height label confidence"},
  };
  for (const Real& r : frames) {
    std::string bytes;
    const std::string_view hex = r.hex;
    for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
      bytes += static_cast<char>(std::stoi(std::string(hex.substr(i, 2)), nullptr, 16));
    out.write(r.ts, r.from_camera
                        ? w::eth(w::udp4(kCamera, kBench, r.camera_port, r.bench_port, bytes))
                        : w::eth(w::udp4(kBench, kCamera, r.bench_port, r.camera_port, bytes)));
    fields << r.fields << '\n';
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: ws_captures OUTDIR SOURCE_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  if (int rc = write_forms(dir)) return rc;
  if (int rc = write_vectors(dir, argv[2])) return rc;
  if (int rc = write_tcp(dir)) return rc;
  if (int rc = write_c12_push(dir)) return rc;
  if (int rc = write_sip_bench(dir)) return rc;
  return write_heuristic(dir);
}
