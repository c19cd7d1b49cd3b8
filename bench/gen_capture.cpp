// Generates a realistic TOP capture for benchmarks: a few autopilot clients
// talking to SkyDroid and Topotek gimbals, written with libpcap.
//
//   gen_capture FRAMES OUT [SEED] [udp|tcp|serial]
//
// Mix: angle and speed commands with their echoes (1-20 ms later), version
// and zoom queries, GAC/GIC attitude streams at 50 Hz after GAA/GIA, about
// 3% frames with a wrong checksum, about 5% of datagrams carrying 2-3 frames,
// some CR/LF-terminated frames, some requests never answered.
//
// udp (the default): Ethernet/IPv4/UDP on the devices' ports. tcp: the same
// traffic over TCP port 5000 (as the C10 and C20 serve it), one connection
// per client, every tenth payload split in two segments. serial: the bytes
// of every frame, both directions, as one raw serial dump (no pcap).
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <string_view>

#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"
#include "top/frame.hpp"

using namespace pcapio;

namespace {

enum class Mode { udp, tcp, serial };

struct Gen {
  std::mt19937_64 rng;
  Mode mode;
  std::unique_ptr<PcapWriter> w;  // udp, tcp
  std::FILE* raw = nullptr;       // serial
  std::uint64_t frames = 0, target;
  std::int64_t t = 1714564800LL * 1000000;
  std::uint32_t seq[4][2] = {};  // tcp: next sequence number per client, up and down
  Gen(const char* path, std::uint64_t n, std::uint64_t seed, Mode m)
      : rng(seed), mode(m), target(n) {
    if (mode == Mode::serial)
      raw = std::fopen(path, "wb");
    else
      w = std::make_unique<PcapWriter>(path, 1);
  }
  bool ok() const { return mode == Mode::serial ? raw != nullptr : w->ok(); }
  bool close() {
    if (mode != Mode::serial) {
      w->close();
      return true;
    }
    return std::fclose(raw) == 0;
  }

  unsigned pick(unsigned n) { return static_cast<unsigned>(rng() % n); }
  std::string hex4(int v) {
    char b[8];
    std::snprintf(b, sizeof b, "%04X", v & 0xFFFF);
    return b;
  }
  std::string make(const std::string& body) {
    ++frames;
    std::string f = top::with_checksum(body);
    if (pick(100) < 3) f[f.size() - 1] = f[f.size() - 1] == '0' ? '1' : '0';  // bad checksum
    if (pick(100) < 4) f += "\r\n";
    return f;
  }
  void send(int client, bool up, bool topotek, const std::string& payload) {
    Ip4 c{192, 168, 144, static_cast<std::uint8_t>(10 + client)};
    Ip4 d{192, 168, 144, static_cast<std::uint8_t>(topotek ? 25 : 108)};
    std::uint16_t cp = topotek ? 9004 : static_cast<std::uint16_t>(40000 + client);
    std::uint16_t dp = topotek ? 9003 : 5000;
    if (mode == Mode::serial) {
      std::fwrite(payload.data(), 1, payload.size(), raw);
      return;
    }
    if (mode == Mode::udp) {
      std::string ip = up ? udp4(c, d, cp, dp, payload) : udp4(d, c, dp, cp, payload);
      w->write(t, eth(ip));
      return;
    }
    cp = static_cast<std::uint16_t>(40000 + client);
    dp = 5000;
    std::uint32_t& mine = seq[client][up ? 0 : 1];
    const std::uint32_t theirs = seq[client][up ? 1 : 0];
    // every tenth payload in two segments, cut at a random byte
    const std::size_t cut = payload.size() > 1 && pick(10) == 0
                                ? 1 + pick(static_cast<unsigned>(payload.size() - 1))
                                : payload.size();
    for (std::size_t at = 0; at < payload.size();) {
      const std::size_t end = at < cut ? cut : payload.size();
      const std::string_view part = std::string_view(payload).substr(at, end - at);
      std::string ip = up ? tcp4(c, d, cp, dp, mine, theirs, kAck | kPsh, part)
                          : tcp4(d, c, dp, cp, mine, theirs, kAck | kPsh, part);
      w->write(t, eth(ip));
      mine += static_cast<std::uint32_t>(part.size());
      at = end;
    }
  }
  // One step of one client: a command and (usually) its answer, or stream frames.
  void step() {
    int client = static_cast<int>(pick(4));
    bool topotek = client == 3;
    char a = topotek ? 'P' : 'U';
    t += 200 + pick(800);
    unsigned kind = pick(100);
    if (kind < 45) {  // attitude stream frame
      std::string id = topotek ? "GIC" : "GAC";
      std::string hdr = topotek ? "#tp" : "#TP";
      std::string body = hdr + "G" + a + "Cr" + id + hex4(static_cast<int>(pick(36000)) - 18000) +
                         hex4(static_cast<int>(pick(18000)) - 9000) +
                         hex4(static_cast<int>(pick(200)) - 100);
      std::string p = make(body);
      if (pick(100) < 5) p += make(body);
      send(client, false, topotek, p);
      return;
    }
    std::string req, resp;
    if (kind < 75) {
      std::string id = pick(2) ? "GAY" : "GAP";
      std::string data = hex4(static_cast<int>(pick(18000)) - 9000) + "32";
      req = std::string("#tp") + a + "G6w" + id + data;
      resp = std::string("#tp") + "G" + a + "6w" + id + data;
    } else if (kind < 85) {
      req = std::string("#TP") + a + "G2wPTZ0" + static_cast<char>('0' + pick(8));
      resp = req;
      std::swap(resp[3], resp[4]);
    } else if (kind < 92) {
      req = std::string("#TP") + a + "D2rVER00";
      resp = std::string("#tpD") + a + "6rVER0105" + hex4(static_cast<int>(pick(100))).substr(2);
    } else {
      std::string id = topotek ? "GIA" : "GAA";
      req = std::string("#TP") + a + "G2w" + id + (topotek ? "01" : "32");
      resp = req;
      std::swap(resp[3], resp[4]);
    }
    std::string p = make(req);
    if (pick(100) < 5)
      p += make(std::string("#TP") + a + "G2wPTZ00");  // several frames per datagram
    send(client, true, topotek, p);
    if (pick(100) < 98) {
      t += 1000 + pick(19000);
      send(client, false, topotek, make(resp));
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: gen_capture FRAMES OUT [SEED] [udp|tcp|serial]\n");
    return 2;
  }
  std::uint64_t n = std::strtoull(argv[1], nullptr, 10);
  std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1;
  const std::string mode = argc > 4 ? argv[4] : "udp";
  if (mode != "udp" && mode != "tcp" && mode != "serial") {
    std::fprintf(stderr, "gen_capture: mode %s is not udp, tcp or serial\n", mode.c_str());
    return 2;
  }
  Gen g(argv[2], n, seed, mode == "tcp" ? Mode::tcp : mode == "serial" ? Mode::serial : Mode::udp);
  if (!g.ok()) {
    std::fprintf(stderr, "gen_capture: cannot write %s\n", argv[2]);
    return 2;
  }
  while (g.frames < n) g.step();
  if (!g.close()) {
    std::fprintf(stderr, "gen_capture: cannot write %s\n", argv[2]);
    return 2;
  }
  std::printf("%llu frames\n", static_cast<unsigned long long>(g.frames));
  return 0;
}
