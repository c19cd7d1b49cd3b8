// topsim::Server's state and its transports (private to sim/: server.cpp
// opens and runs them, server_drive.cpp adds what a harness asks of a
// running device).
#pragma once

#include <asio.hpp>
#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "pcapio/writer.hpp"
#include "recording.hpp"
#include "server_line.hpp"
#include "sim/intake.hpp"
#include "sim/server.hpp"
#include "top/device.hpp"
#include "top/dialect.hpp"
#include "udp_copies.hpp"

namespace topsim {

using Clock = std::chrono::steady_clock;

// "127.0.0.1:40000" (IPv6 in brackets).
template <class Endpoint>
std::string endpoint_name(const Endpoint& e) {
  const std::string a = e.address().to_string();
  return (e.address().is_v6() ? "[" + a + "]" : a) + ":" + std::to_string(e.port());
}

// The client end of a serial line or pseudo-terminal, as the recording
// names it (Recording: the bytes from it are TX).
inline const pcapio::Endpoint kLineClient = pcapio::Endpoint::ipv4(0x7F000001u, 9001);

struct Server::Impl {
  ServerConfig cfg;
  asio::io_context io;
  Device device;
  FaultInjector faults;
  Clock::time_point start = Clock::now();
  ServerStats stats;
  std::unique_ptr<Recording> pcap;
  asio::steady_timer stream_timer{io};
  asio::steady_timer reboot_timer{io};  // the reboot= fault (server_drive.cpp)
  void arm_reboot();

  struct UdpPort {
    explicit UdpPort(asio::io_context& io) : sock(io) {}
    asio::ip::udp::socket sock;
    asio::ip::udp::endpoint from;
    std::string buf = std::string(65536, '\0');
    top::StreamDecoder dec;
    std::uint16_t port = 0;
  };
  std::vector<std::unique_ptr<UdpPort>> udp;  // the model's port, then extra ones (C10: 9002)
  // UDP: where the device's datagrams go (sim/fanout.hpp), and the port of
  // its own they leave from (UdpTraits::ephemeral_reply_port), if any.
  std::optional<Fanout> fanout;
  std::unique_ptr<UdpPort> reply_sock;
  asio::ip::address last_host;  // the client's host: where the last request came from
  bool have_host = false;
  std::optional<asio::ip::tcp::acceptor> acceptor;
  std::uint16_t bound_port = 0;
  std::string pty_path;
  int pty_slave = -1;

  // Where the device's frames go, and how to record them.
  struct Peer {
    std::function<void(std::string)> send;  // a stream link's line
    pcapio::Endpoint remote, local;         // the request's ends (the line's)
    bool stream_link = false;
    std::string_view link = "udp";  // for on_traffic
    std::string name;               // the peer, for on_traffic
    // UDP: the socket the request reached, the client's host and the ports
    // a reply goes to there (a push's: the fan-out's when it leaves).
    UdpPort* served = nullptr;
    asio::ip::address host;
    std::vector<std::uint16_t> ports;
    bool push = false;
  };
  Peer stream_peer;  // the last peer that sent a request (receives pushes)
  bool have_stream_peer = false;

  explicit Impl(ServerConfig c)
      : cfg(std::move(c)), device(cfg.model, device_options()), faults(cfg.faults, cfg.seed) {}

  DeviceOptions device_options() const {
    DeviceOptions o = cfg.device_options;
    o.swap_addresses = !cfg.faults.no_swap;
    o.tmp_quirk = o.tmp_quirk || cfg.faults.tmp_quirk;
    o.faults = cfg.faults.device;
    return o;
  }

  // A power cycle: the device's state as at start, crash and hang cleared;
  // it forgets who asked.
  void restart() {
    device = Device(cfg.model, device_options());
    faults.restart();
    stream_timer.cancel();
    if (fanout) fanout.emplace(device.udp_traits(), fanout->client_port());
    have_stream_peer = false;
  }
  void wait_hangup(std::shared_ptr<asio::signal_set> sig) {
    sig->async_wait([this, sig](std::error_code ec, int) {
      if (ec) return;
      restart();
      wait_hangup(sig);
    });
  }

  std::uint64_t now_us() const {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count());
  }

  std::uint64_t line_busy_until = 0;  // stream links: one write at a time

  void emit(const Peer& peer, const std::vector<std::string>& frames) {
    std::vector<Emission> em;
    for (const auto& f : frames) faults.apply(f, peer.stream_link, em);
    const std::uint64_t now = now_us();
    for (auto& e : em) {
      stats.frames_out.fetch_add(1, std::memory_order_relaxed);
      if (peer.stream_link) {
        // A split frame's second half must not be overtaken by the next frame.
        const std::uint64_t at = std::max(now + e.delay_us, line_busy_until);
        line_busy_until = at;
        e.delay_us = at - now;
      }
      if (e.delay_us == 0) {
        deliver(peer, std::move(e.bytes));
        continue;
      }
      auto t = std::make_shared<asio::steady_timer>(io, std::chrono::microseconds(e.delay_us));
      t->async_wait([this, t, peer, bytes = std::move(e.bytes)](std::error_code ec) mutable {
        if (ec) return;
        deliver(peer, std::move(bytes));
      });
    }
  }

  // Sends one write of the device to `peer`: recorded, told, sent.
  void deliver(const Peer& peer, std::string bytes) {
    if (peer.served) {
      send_udp(peer, bytes);
      return;
    }
    if (pcap) pcap->write(peer.local, peer.remote, bytes);
    if (cfg.on_traffic) cfg.on_traffic(Traffic{peer.link, '>', peer.name, bytes});
    peer.send(std::move(bytes));
  }

  static std::uint32_t v4(const asio::ip::address& a) {
    return a.is_v4() ? a.to_v4().to_uint() : 0x7F000001u;
  }

  // One datagram of the device to every port of the client's host the
  // fan-out names, from the reply port (or the port the request reached):
  // each copy recorded and told, all sent by one sendmmsg(2) so that they
  // leave together (top::fan_out_copy_window_us).
  void send_udp(const Peer& peer, const std::string& bytes) {
    UdpPort& from = reply_sock ? *reply_sock : *peer.served;
    const std::vector<std::uint16_t> ports = peer.push && fanout ? fanout->push() : peer.ports;
    std::vector<asio::ip::udp::endpoint> to;
    to.reserve(ports.size());
    std::error_code e;
    const auto local = from.sock.local_endpoint(e);
    const pcapio::Endpoint ours =
        pcapio::Endpoint::ipv4(e ? 0x7F000001u : v4(local.address()), from.port);
    for (const std::uint16_t port : ports) {
      to.emplace_back(peer.host, port);
      if (pcap) pcap->write(ours, pcapio::Endpoint::ipv4(v4(peer.host), port), bytes);
      if (cfg.on_traffic)
        cfg.on_traffic(Traffic{"udp", '>',
                               endpoint_name(to.back()) +
                                   (reply_sock ? " from port " + std::to_string(from.port) : ""),
                               bytes});
    }
    send_copies(from.sock.native_handle(), to, bytes);
  }

  Intake intake(Link link) { return Intake{device, link, &faults}; }

  // `keep` holds the decoder's owner (a TCP connection) alive for timers.
  void on_bytes(top::StreamDecoder& dec, std::string_view bytes, bool datagram, const Peer& peer,
                Link link, std::shared_ptr<void> keep = nullptr) {
    stats.bytes_in.fetch_add(bytes.size(), std::memory_order_relaxed);
    if (pcap) pcap->write(peer.remote, peer.local, bytes);
    if (cfg.on_traffic) cfg.on_traffic(Traffic{peer.link, '<', peer.name, bytes});
    std::vector<std::string> out;
    const std::size_t frames = intake(link).take(dec, bytes, datagram, now_us(), out);
    stats.frames_in.fetch_add(frames, std::memory_order_relaxed);
    if (!datagram && dec.buffered() > 0) arm_quiet(dec, peer, link, std::move(keep));
    stream_peer = peer;
    stream_peer.push = true;  // UDP: pushes go where the fan-out says when they leave
    have_stream_peer = true;
    if (!out.empty()) emit(peer, out);
    arm_stream_timer();
  }

  // Bytes held on a stream (a frame failing its checksum waits for
  // look-ahead): once the line is quiet (top::quiet_line_ms), decide on them.
  void arm_quiet(top::StreamDecoder& dec, const Peer& peer, Link link, std::shared_ptr<void> keep) {
    const std::uint64_t fed = dec.fed();
    auto t =
        std::make_shared<asio::steady_timer>(io, std::chrono::milliseconds(top::quiet_line_ms));
    t->async_wait([this, t, &dec, fed, peer, link, keep](std::error_code ec) {
      if (ec || dec.fed() != fed || dec.buffered() == 0) return;
      dec.finish();
      std::vector<std::string> out;
      const std::size_t frames = intake(link).drain(dec, now_us(), out);
      stats.frames_in.fetch_add(frames, std::memory_order_relaxed);
      dec.reset();
      if (!out.empty()) emit(peer, out);
    });
  }

  void arm_stream_timer() {
    const std::uint64_t next = device.next_timer();
    if (next == std::numeric_limits<std::uint64_t>::max()) return;
    stream_timer.expires_at(start + std::chrono::microseconds(next));
    stream_timer.async_wait([this](std::error_code ec) {
      if (ec) return;
      std::vector<std::string> out;
      device.poll(now_us(), out);
      if (have_stream_peer && !faults.hung() && !out.empty()) emit(stream_peer, out);
      arm_stream_timer();
    });
  }

  // UDP ----------------------------------------------------------------
  void udp_receive(UdpPort& u) {
    u.sock.async_receive_from(
        asio::buffer(u.buf), u.from, [this, &u](std::error_code ec, std::size_t n) {
          if (ec == asio::error::operation_aborted) return;
          if (!ec) {
            const bool new_host = !have_host || u.from.address() != last_host;
            last_host = u.from.address();
            have_host = true;
            Peer p;
            p.served = &u;
            p.host = u.from.address();
            p.ports = fanout->request(u.from.port(), new_host);
            p.remote = pcapio::Endpoint::ipv4(v4(u.from.address()), u.from.port());
            std::error_code e;
            const auto local = u.sock.local_endpoint(e);
            p.local = pcapio::Endpoint::ipv4(e ? 0x7F000001u : v4(local.address()), u.port);
            if (cfg.on_traffic) p.name = endpoint_name(u.from);
            on_bytes(u.dec, std::string_view(u.buf.data(), n), true, p, Link::network);
          }
          udp_receive(u);
        });
  }

  // TCP ----------------------------------------------------------------
  using TcpLine = Line<asio::ip::tcp::socket>;
  struct Conn {
    std::shared_ptr<TcpLine> line;
    top::StreamDecoder dec;
    std::string buf = std::string(4096, '\0');
  };
  void tcp_accept() {
    acceptor->async_accept([this](std::error_code ec, asio::ip::tcp::socket s) {
      if (ec == asio::error::operation_aborted) return;
      if (!ec) {
        auto c = std::make_shared<Conn>();
        std::error_code nd;
        s.set_option(asio::ip::tcp::no_delay(true), nd);
        c->line = std::make_shared<TcpLine>(std::move(s));
        tcp_read(c);
      }
      tcp_accept();
    });
  }
  void tcp_read(std::shared_ptr<Conn> c) {
    c->line->stream().async_read_some(
        asio::buffer(c->buf), [this, c](std::error_code ec, std::size_t n) {
          if (ec) return;  // closed: the connection's state goes with it
          auto& sock = c->line->stream();
          std::error_code e1, e2;
          auto re = sock.remote_endpoint(e1);
          auto le = sock.local_endpoint(e2);
          Peer p;
          p.remote = pcapio::Endpoint::ipv4(e1 ? 0x7F000001u : re.address().to_v4().to_uint(),
                                            e1 ? std::uint16_t{0} : re.port());
          p.local =
              pcapio::Endpoint::ipv4(e2 ? 0x7F000001u : le.address().to_v4().to_uint(), bound_port);
          std::weak_ptr<TcpLine> w = c->line;
          p.send = [w](std::string b) {
            if (auto l = w.lock(); l && l->open) l->write(std::move(b));
          };
          p.stream_link = true;
          p.link = "tcp";
          if (cfg.on_traffic && !e1) p.name = endpoint_name(re);
          on_bytes(c->dec, std::string_view(c->buf.data(), n), false, p, Link::network, c);
          tcp_read(c);
        });
  }

  // pty / serial ---------------------------------------------------------
  using PtyLine = Line<asio::posix::stream_descriptor>;
  using SerialLine = Line<asio::serial_port>;
  std::shared_ptr<PtyLine> pty_line;
  std::shared_ptr<SerialLine> serial_line;
  top::StreamDecoder line_decoder;
  std::string line_buf = std::string(4096, '\0');

  Peer line_peer() {
    Peer p;
    // The line's ends, for the recording (a line log: TX from the client).
    p.remote = kLineClient;
    p.local = pcapio::Endpoint::ipv4(0x7F000001u, 9000);
    p.stream_link = true;
    p.link = pty_line ? "pty" : "serial";
    p.name = pty_line ? pty_path : cfg.device;
    if (pty_line)
      p.send = [l = pty_line](std::string b) { l->write(std::move(b)); };
    else
      p.send = [l = serial_line](std::string b) { l->write(std::move(b)); };
    return p;
  }
  template <class L>
  void line_read(std::shared_ptr<L> l) {
    l->stream().async_read_some(asio::buffer(line_buf), [this, l](std::error_code ec,
                                                                  std::size_t n) {
      if (ec == asio::error::operation_aborted) return;
      if (ec) {
        // A pty master reads EIO while no client has the slave open; wait.
        auto t = std::make_shared<asio::steady_timer>(io, std::chrono::milliseconds(20));
        t->async_wait([this, l, t](std::error_code e) {
          if (!e) line_read(l);
        });
        return;
      }
      on_bytes(line_decoder, std::string_view(line_buf.data(), n), false, line_peer(), Link::uart);
      line_read(l);
    });
  }
};

}  // namespace topsim
