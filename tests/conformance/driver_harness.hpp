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
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "conf/link.hpp"
#include "conf/transport.hpp"
#include "loopback.hpp"
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

// How a client's UDP socket takes what a device sends, as the public
// clients' do (a real Topotek camera answers from a port of its own to the
// asking port and to UDP 9004: top::TraitKind ephemeral_reply_port, fan_out).
enum class UdpClient : std::uint8_t {
  // One socket on an ephemeral port, not connected: sendto() the device,
  // take what comes from any port of its host. ArduPilot's NET_Pn UDP client
  // with PR #34227 (AP_Networking: accept UDP client replies from a
  // different source port, tested on a Topotek KHP415), and topconf.
  unconnected,
  // One socket connect()ed to the device's address and port: the kernel
  // drops what comes from another port. ArduPilot master's NET_Pn UDP
  // client (libraries/AP_Networking/AP_Networking_port.cpp @ d0678504,
  // udp_client_loop()); it hears nothing from a real Topotek camera.
  connected,
  // Requests from an unbound socket (never read), answers on a second one
  // bound to UDP 9004 (SO_REUSEADDR, not connected, any source): PixEagle's
  // GimbalInterface (src/classes/gimbal_interface.py @ 0724458,
  // @ 2608012 and @ 3bea324, _init_listening_socket, _send_command). PixEagle binds
  // 0.0.0.0:9004; here 9004 of the test's own loopback host, the device's.
  pixeagle,
};

// The client's end of a UDP link to udp://HOST:PORT as `how` makes it.
std::unique_ptr<topconf::Transport> open_udp_client(UdpClient how, const std::string& host,
                                                    std::uint16_t port, top::Model model);

// Runs `client` against topsim for `duration_ms` over `kind` (udp, tcp or pty),
// with `faults` (topsim --fault). The server records the run to `record`
// (empty: none). Over UDP and TCP the device is served on its model's port
// (top::default_port: Topotek 9003, SkyDroid 5000) of a loopback host of
// the run's own (loopback.hpp), as `topsim` serves it, and the client's
// socket is `how`. Throws on a link that cannot be opened.
inline DriverRun run_driver(DriverClient& client, top::Model model, topsim::TransportKind kind,
                            std::uint64_t duration_ms, const std::string& record,
                            topsim::DeviceOptions options = {},
                            const topsim::FaultConfig& faults = {},
                            UdpClient how = UdpClient::unconnected) {
  topsim::ServerConfig cfg;
  cfg.model = model;
  cfg.kind = kind;
  cfg.record = record;
  cfg.device_options = options;
  cfg.faults = faults;
  cfg.host = own_loopback();
  cfg.port = topsim::default_port(model);
  RunningServer s(cfg);
  std::unique_ptr<topconf::Transport> t =
      kind == topsim::TransportKind::udp
          ? open_udp_client(how, cfg.host, s.server.port(), model)
          : topconf::open_transport(
                kind == topsim::TransportKind::tcp
                    ? "tcp://" + cfg.host + ":" + std::to_string(s.server.port())
                    : "serial:" + s.server.pty_path(),
                model, 0);
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

// What a test tells topdump of a recording of topsim `model` over `kind`:
// the dialect (topdump reads the first frames of a serial line's recording
// before it could tell it; not the model, whose field traits a
// --profile document device does not have).
inline std::string topdump_args(top::Model model, topsim::TransportKind) {
  return "--dialect " + std::string(top::to_string(top::dialect_of(model)));
}
// Where a test records topsim over `kind` (`stem` and the link's name): a
// pcap for UDP and TCP, topdump's line log for a pseudo-terminal (topsim
// --record: a serial line's recording says it was one).
inline std::string recording_path(const std::string& stem, topsim::TransportKind kind) {
  const bool line = kind == topsim::TransportKind::pty || kind == topsim::TransportKind::serial;
  return std::string(TOPKIT_BINARY_DIR) + "/" + stem + (line ? ".log" : ".pcap");
}

// Runs the built `topdump read --json FILE` and collects its findings of
// `min_severity` or worse ("info", "warning", "error"). `args` go before
// the file (--model sip).
Dump topdump_findings(const std::string& pcap, const std::string& min_severity = "warning",
                      const std::string& args = {});
JsonLines topdump_read_json(const std::string& pcap, const std::string& args);
// Every finding as "code (ident, frame N): message" lines, for a test's failure text.
std::string describe(const Dump& d);
