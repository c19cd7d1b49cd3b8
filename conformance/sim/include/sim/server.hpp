// topsim's transports: the device model served over UDP, TCP, a
// pseudo-terminal or a serial port with Asio, with fault injection and an
// optional pcap recording.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/device.hpp"
#include "sim/faults.hpp"

namespace topsim {

enum class TransportKind : std::uint8_t { udp, tcp, pty, serial };

// One datagram (or chunk of a byte stream) on a transport, for topsim
// --verbose: received ('<') or sent ('>').
struct Traffic {
  std::string_view link;  // "udp", "tcp", "pty", "serial"
  char dir = '<';
  std::string peer;  // "127.0.0.1:40000" or the line's path
  std::string_view bytes;
};

struct ServerConfig {
  top::Model model = top::Model::c12;
  TransportKind kind = TransportKind::udp;
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;  // 0: ephemeral (tests); the CLI fills the model's port
  // UDP: the client's port the device sends to (sim/fanout.hpp); unset: the
  // model's (top::client_port: Topotek 9004, SkyDroid none); 0: none, the
  // asking port gets the replies. Where replies go from, and to whom else,
  // the device's UDP traits say (DeviceOptions; Device::udp_traits).
  std::optional<std::uint16_t> reply_port;
  std::vector<std::uint16_t> extra_udp_ports;  // also served (C10: UDP 9002)
  std::string device;                          // serial device path
  unsigned baud = 115200;
  FaultConfig faults;
  std::uint64_t seed = 1;
  std::string record;  // pcap path, empty for none
  DeviceOptions device_options;
  // Told of every datagram or chunk received and sent (null: nobody).
  std::function<void(const Traffic&)> on_traffic;
};

// The default UDP/TCP port of a model: SkyDroid 5000, Topotek 9003.
std::uint16_t default_port(top::Model m) noexcept;
// The network transport a model speaks when none is chosen: TCP for the
// C20 (SkyDroid 2.1: TCP 5000 only), UDP for the others.
TransportKind default_transport(top::Model m) noexcept;
// The other UDP ports a model serves by default (C10: 9002); from
// top::known_ports().
std::vector<std::uint16_t> extra_udp_ports(top::Model m);

struct ServerStats {
  std::atomic<std::uint64_t> bytes_in{0};
  std::atomic<std::uint64_t> frames_in{0};
  std::atomic<std::uint64_t> frames_out{0};
};

class Server {
 public:
  // Opens the socket, pseudo-terminal or serial port; throws
  // std::runtime_error with a message naming what failed.
  explicit Server(ServerConfig cfg);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  std::uint16_t port() const noexcept;           // bound UDP/TCP port
  std::vector<std::uint16_t> udp_ports() const;  // every bound UDP port
  // UDP: the port replies and pushes leave from, when the device sends from
  // a port of its own (UdpTraits::ephemeral_reply_port), else 0 (from the
  // port the request reached).
  std::uint16_t reply_from_port() const noexcept;
  // UDP: the client port it sends to (0: none) and its UDP traits.
  std::uint16_t client_port() const noexcept;
  UdpTraits udp_traits() const noexcept;
  // Stops run() on SIGINT/SIGTERM (asio::signal_set; for the CLI).
  void stop_on_signals();
  // Restarts the device on SIGHUP, as restart() does (for `topconf fuzz
  // --restart-cmd 'kill -HUP PID'`; the CLI).
  void restart_on_hangup();
  // A power cycle of the device (callable from any thread): its state as at
  // start, firmware faults (crash-on, hang-on) cleared; sockets stay open.
  void restart();
  std::string pty_path() const;  // slave path for --pty
  // Runs `fn` on the server's thread with the device and the device's clock
  // (microseconds since the server started), and returns once it ran: how a
  // harness samples the device's truth while it serves (topconf drive).
  // false when the server did not run it within 1 s (not running).
  bool visit(const std::function<void(const Device&, std::uint64_t now_us)>& fn);
  // The device changes case in place (topconf drive --persistent): new
  // faults and device options, the state and the link kept
  // (Device::reconfigure). Callable from any thread; returns once done
  // (false when the server did not run it within 1 s).
  bool reconfigure(const FaultConfig& faults, const DeviceOptions& options);
  // Microseconds since the server started (the device's clock).
  std::uint64_t now_us() const;
  // Serves until stop() (callable from any thread).
  void run();
  void stop();
  const ServerStats& stats() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace topsim
