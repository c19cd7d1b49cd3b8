// bench_to_pcap: turns one session of the PixEagle gimbal bench's event log
// (events.jsonl, one JSON object per line) into a pcap of the UDP datagrams
// it recorded, with their times, ports, addresses and bytes as recorded.
//
// The event log (alireza787b/PixEagle @ 3bea324,
// docs/reporting/agent-ops/codex-modernization/evidence/
// 2026-09-17-gimbal-control-bench/<session>/events.jsonl) holds, per event,
// `utc` (ISO 8601 with microseconds) and `kind`:
//   start       `host`: the camera's IPv4 address
//   bind        `port`: a UDP port the bench bound, in the order it bound them
//   tx          `local_port`, `hex`: a datagram the bench sent to the camera
//   cleanup_tx  `hex`: the same from the bench's first socket (the bench
//               script sends its cleanup with sockets[0].sendto; its
//               events record no port: scripts/<script_sha256>.py)
//   rx          `local_port`, `peer` [address, port], `hex`: a datagram the
//               bench received
//   summary     `received`: per "address:port->local_port", the rx count
// Every other kind (operator_clearance, video decoding, errors) is no
// datagram. The bench sends every datagram to the camera's UDP 9003 (its
// script: `sendto(data, (HOST, 9003))`); --camera-port changes it. Its own
// address is not in the log: --host gives it.
//
// The pcap is raw IPv4 (LINKTYPE_RAW): the log records no MAC address, and
// every IPv4 identification is 0 (not recorded). A datagram delivered to
// several ports is one packet per delivery, as the bench received them.
#include <pcap/pcap.h>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "capture/time.hpp"
#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"

namespace {

using nlohmann::json;

struct Args {
  std::string in, out, host = "192.168.0.167";
  std::uint16_t camera_port = 9003;
};

std::optional<pcapio::Ip4> ip4(const std::string& s) {
  pcapio::Ip4 a{};
  const char* p = s.data();
  const char* end = p + s.size();
  for (int i = 0; i < 4; ++i) {
    unsigned v = 0;
    auto r = std::from_chars(p, end, v);
    if (r.ec != std::errc() || v > 255) return std::nullopt;
    a[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v);
    p = r.ptr;
    if (i < 3) {
      if (p == end || *p != '.') return std::nullopt;
      ++p;
    }
  }
  if (p != end) return std::nullopt;
  return a;
}

std::optional<std::string> unhex(const std::string& h) {
  if (h.size() % 2) return std::nullopt;
  std::string out;
  out.reserve(h.size() / 2);
  for (std::size_t i = 0; i < h.size(); i += 2) {
    unsigned v = 0;
    auto r = std::from_chars(h.data() + i, h.data() + i + 2, v, 16);
    if (r.ec != std::errc() || r.ptr != h.data() + i + 2) return std::nullopt;
    out.push_back(static_cast<char>(v));
  }
  return out;
}

// Removes what a failed run wrote, when it is a file of its own: never a
// device (/dev/full) or anything else the path named before.
void discard(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(std::filesystem::symlink_status(path, ec)))
    std::filesystem::remove(path, ec);
}

int usage() {
  std::fprintf(stderr,
               "usage: bench_to_pcap [--host IPV4] [--camera-port PORT] EVENTS.jsonl OUT.pcap\n"
               "  --host         the bench host's address (not in the log; default 192.168.0.167)\n"
               "  --camera-port  the camera port the bench sends to (default 9003)\n");
  return 2;
}

// One converted session; errors name the file and line and stop the run.
class Session {
 public:
  Session(const Args& a, pcapio::Ip4 host) : args_(a), host_(host) {}

  bool line(const std::string& text, std::size_t n, pcapio::PcapWriter& w) {
    const json e = json::parse(text, nullptr, false);
    if (e.is_discarded() || !e.is_object()) return fail(n, "not a JSON object");
    const std::string kind = e.value("kind", std::string());
    if (kind == "start") {
      const auto cam = ip4(e.value("host", std::string()));
      if (!cam) return fail(n, "start event without an IPv4 host");
      camera_ = *cam;
      camera_text_ = e.value("host", std::string());
      return true;
    }
    if (kind == "bind") {
      if (!e.contains("port") || !e["port"].is_number_unsigned())
        return fail(n, "bind event without a port");
      binds_.push_back(e["port"].get<std::uint16_t>());
      return true;
    }
    if (kind == "summary" && e.contains("received") && e["received"].is_object()) {
      for (const auto& [k, v] : e["received"].items())
        if (v.is_number_unsigned()) summary_[k] = v.get<std::uint64_t>();
      has_summary_ = true;
      return true;
    }
    if (kind != "tx" && kind != "rx" && kind != "cleanup_tx") return true;
    if (!camera_) return fail(n, kind + " event before the start event named the camera");
    const auto ts = topdump::parse_time(e.value("utc", std::string()));
    if (!ts) return fail(n, "no ISO 8601 utc time");
    const auto bytes = unhex(e.value("hex", std::string()));
    if (!bytes || bytes->empty()) return fail(n, "no hex bytes");
    std::string packet;
    if (kind == "rx") {
      const json& peer = e.value("peer", json());
      if (!peer.is_array() || peer.size() != 2 || !peer[0].is_string() ||
          !peer[1].is_number_unsigned() || !e.contains("local_port"))
        return fail(n, "rx event without peer [address, port] and local_port");
      const auto from = ip4(peer[0].get<std::string>());
      if (!from) return fail(n, "rx peer is not an IPv4 address");
      const auto sport = peer[1].get<std::uint16_t>();
      const auto dport = e["local_port"].get<std::uint16_t>();
      packet = pcapio::udp4(*from, host_, sport, dport, *bytes);
      ++received_[peer[0].get<std::string>() + ":" + std::to_string(sport) + "->" +
                  std::to_string(dport)];
      ++rx_;
    } else {
      std::uint16_t sport = 0;
      if (kind == "tx") {
        if (!e.contains("local_port") || !e["local_port"].is_number_unsigned())
          return fail(n, "tx event without local_port");
        sport = e["local_port"].get<std::uint16_t>();
        ++tx_;
      } else {
        if (binds_.empty()) return fail(n, "cleanup_tx before any bind event");
        sport = binds_.front();
        ++cleanup_;
      }
      packet = pcapio::udp4(host_, *camera_, sport, args_.camera_port, *bytes);
    }
    w.write(*ts, packet);
    return true;
  }

  // The rx counts against the session's summary; false when they differ.
  bool check_summary() const {
    if (!has_summary_ || summary_ == received_) return true;
    std::fprintf(stderr, "bench_to_pcap: error: %s: the rx events do not add up to the summary\n",
                 args_.in.c_str());
    return false;
  }
  void report() const {
    std::printf("%s: %llu tx, %llu cleanup tx, %llu rx (camera %s) -> %s\n", args_.in.c_str(),
                static_cast<unsigned long long>(tx_), static_cast<unsigned long long>(cleanup_),
                static_cast<unsigned long long>(rx_), camera_text_.c_str(), args_.out.c_str());
  }

 private:
  bool fail(std::size_t n, const std::string& why) const {
    std::fprintf(stderr, "bench_to_pcap: error: %s:%zu: %s\n", args_.in.c_str(), n, why.c_str());
    return false;
  }
  const Args& args_;
  pcapio::Ip4 host_;
  std::optional<pcapio::Ip4> camera_;
  std::string camera_text_;
  std::vector<std::uint16_t> binds_;
  std::map<std::string, std::uint64_t> summary_, received_;
  bool has_summary_ = false;
  std::uint64_t tx_ = 0, rx_ = 0, cleanup_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  Args a;
  std::vector<std::string> pos;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    if ((s == "--host" || s == "--camera-port") && i + 1 < argc) {
      const std::string v = argv[++i];
      if (s == "--host") {
        a.host = v;
      } else {
        unsigned p = 0;
        auto r = std::from_chars(v.data(), v.data() + v.size(), p);
        if (r.ec != std::errc() || r.ptr != v.data() + v.size() || p == 0 || p > 65535)
          return usage();
        a.camera_port = static_cast<std::uint16_t>(p);
      }
    } else if (s == "-h" || s == "--help") {
      usage();
      return 0;
    } else if (!s.empty() && s[0] == '-') {
      return usage();
    } else {
      pos.push_back(s);
    }
  }
  if (pos.size() != 2) return usage();
  a.in = pos[0];
  a.out = pos[1];
  const auto host = ip4(a.host);
  if (!host) {
    std::fprintf(stderr, "bench_to_pcap: error: --host %s is not an IPv4 address\n",
                 a.host.c_str());
    return 2;
  }
  std::ifstream in(a.in);
  if (!in) {
    std::fprintf(stderr, "bench_to_pcap: error: %s: cannot open\n", a.in.c_str());
    return 2;
  }
  pcapio::PcapWriter w(a.out, DLT_RAW);
  if (!w.ok()) {
    std::fprintf(stderr, "bench_to_pcap: error: %s: %s\n", a.out.c_str(), w.error().c_str());
    return 2;
  }
  Session s(a, *host);
  std::string text;
  std::size_t n = 0;
  while (std::getline(in, text)) {
    ++n;
    if (text.empty()) continue;
    if (!s.line(text, n, w)) {
      w.close();
      discard(a.out);
      return 2;
    }
  }
  if (!w.finish()) {
    std::fprintf(stderr, "bench_to_pcap: error: %s: the write failed\n", a.out.c_str());
    discard(a.out);
    return 2;
  }
  if (!s.check_summary()) return 2;
  s.report();
  return 0;
}
