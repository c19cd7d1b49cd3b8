// Driver-like clients against topsim over real links (issue 28 item 3).
// A DriverClient holds what a public autopilot driver does, carried over
// as facts from reading its source (docs/sources/ardupilot.md): what it
// sends and when, and how it reads what comes back. This harness runs one
// over a real pseudo-terminal, UDP socket or TCP connection against an in-process topsim
// server that records the run to a pcap, and reads that recording back
// with the built topdump.
#pragma once

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "conf/link.hpp"
#include "conf/transport.hpp"
#include "running_server.hpp"
#include "sim/server.hpp"
#include "top/dialect.hpp"
#include "top/frame.hpp"

class DriverClient {
 public:
  virtual ~DriverClient() = default;
  // The address the driver's requests carry as their source (U on a
  // serial line, the Topotek network client P: top::client_address).
  char client = 'U';
  // The frames the driver sends at `now_us`, appended to `out`; returns
  // when it wants to be called next.
  virtual std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) = 0;
  // A frame the driver received at `now_us`.
  virtual void on_frame(const top::Frame& f, std::uint64_t now_us) = 0;
};

struct DriverLink {
  topsim::TransportKind kind = topsim::TransportKind::udp;
  const char* name() const {
    switch (kind) {
      case topsim::TransportKind::udp:
        return "udp";
      case topsim::TransportKind::tcp:
        return "tcp";
      default:
        return "pty";
    }
  }
};

// The links a driver client runs over against `model` (issue 28 item 2:
// "over a pty, UDP and TCP where the link rules allow"): a pty (a serial
// line: AP_Mount_Topotek's MNT1_TYPE=12 at 115200, AP_Mount_SkyDroid's
// serial port), then UDP and TCP where top::known_ports() gives the model a
// device port on them. By those rules only the C10 and the C20 have a TCP
// port (SkyDroid 2.1.1); the Topotek document gives the SIP UDP 9003 and a
// UART, and the C12 and C13 have UDP 5000 (and 12580) only: none of the
// drivers' models (sip, c12, c13) is served over TCP (docs/FIELD.md, Ports).
inline std::vector<topsim::TransportKind> driver_links(top::Model model) {
  std::vector<topsim::TransportKind> links{topsim::TransportKind::pty};
  bool udp = false, tcp = false;
  for (const top::PortSpec& p : top::known_ports())
    if (!p.client && (p.models & top::model_bit(model))) (p.tcp ? tcp : udp) = true;
  if (udp) links.push_back(topsim::TransportKind::udp);
  if (tcp) links.push_back(topsim::TransportKind::tcp);
  return links;
}

struct DriverRun {
  std::uint64_t sent = 0, received = 0;  // frames
  std::uint64_t start_us = 0;            // on the client's clock
};

// Runs `client` against topsim for `duration_ms` over `kind` (udp, tcp or pty),
// with `faults` (topsim --fault). The server records the run to `record`
// (empty: none). Throws on a link that cannot be opened.
inline DriverRun run_driver(DriverClient& client, top::Model model, topsim::TransportKind kind,
                            std::uint64_t duration_ms, const std::string& record,
                            topsim::DeviceOptions options = {},
                            const topsim::FaultConfig& faults = {}) {
  topsim::ServerConfig cfg;
  cfg.model = model;
  cfg.kind = kind;
  cfg.record = record;
  cfg.device_options = options;
  cfg.faults = faults;
  RunningServer s(cfg);
  const std::string target =
      kind == topsim::TransportKind::udp   ? "udp://127.0.0.1:" + std::to_string(s.server.port())
      : kind == topsim::TransportKind::tcp ? "tcp://127.0.0.1:" + std::to_string(s.server.port())
                                           : "serial:" + s.server.pty_path();
  auto t = topconf::open_transport(target, model, 0);
  client.client = t->client_address();
  topconf::FrameLink link(*t, nullptr, 4096);
  DriverRun run;
  run.start_us = link.now();
  const std::uint64_t end = run.start_us + duration_ms * 1000;
  std::uint64_t next = run.start_us;
  std::vector<std::string> out;
  for (std::uint64_t now = link.now(); now < end; now = link.now()) {
    if (now >= next) {
      out.clear();
      next = client.tick(now, out);
      for (const std::string& f : out) link.send(f);
      run.sent += out.size();
      continue;
    }
    topconf::Received r;
    while (link.next(std::min(next, end), r)) {
      client.on_frame(r.frame, r.t_us);
      ++run.received;
    }
  }
  return run;
}

// A finding in `topdump read --json`: a session finding line, or one of a
// frame's findings (then `frame` is its index and `ident` its identifier).
struct DumpFinding {
  std::string code, severity, message, ident;
  long long frame = -1;
};

struct Dump {
  int status = -1;  // topdump's exit status
  std::vector<DumpFinding> findings;
  std::size_t lines = 0;
};

// Runs the built `topdump read --json FILE`: its exit status (-1 when it
// could not run) and each line as JSON (discarded when it does not parse).
struct JsonLines {
  int status = -1;
  std::vector<std::pair<std::string, nlohmann::json>> lines;  // text, parsed
};
JsonLines topdump_read_json(const std::string& pcap);

// Runs the built `topdump read --json FILE` and collects its findings of
// `min_severity` or worse ("info", "warning", "error").
Dump topdump_findings(const std::string& pcap, const std::string& min_severity = "warning");
// Every finding as "code (ident, frame N): message" lines, for a test's failure text.
std::string describe(const Dump& d);
