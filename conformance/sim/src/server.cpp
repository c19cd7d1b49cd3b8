#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "server_impl.hpp"

namespace topsim {

Server::Server(ServerConfig cfg) : impl_(std::make_unique<Impl>(std::move(cfg))) {
  Impl& m = *impl_;
  if (!m.cfg.record.empty()) {
    const bool line = m.cfg.kind == TransportKind::pty || m.cfg.kind == TransportKind::serial;
    m.pcap = std::make_unique<Recording>(m.cfg.record, line, m.cfg.kind == TransportKind::tcp,
                                         kLineClient);
  }
  std::error_code ec;
  switch (m.cfg.kind) {
    case TransportKind::udp: {
      auto addr = asio::ip::make_address(m.cfg.host, ec);
      if (ec) throw std::runtime_error("udp: bad host '" + m.cfg.host + "': " + ec.message());
      std::vector<std::uint16_t> ports = {m.cfg.port};
      ports.insert(ports.end(), m.cfg.extra_udp_ports.begin(), m.cfg.extra_udp_ports.end());
      for (const std::uint16_t port : ports) {
        auto u = std::make_unique<Impl::UdpPort>(m.io);
        asio::ip::udp::endpoint ep(addr, port);
        u->sock.open(ep.protocol(), ec);
        if (!ec) u->sock.bind(ep, ec);
        if (ec)
          throw std::runtime_error("udp " + m.cfg.host + ":" + std::to_string(port) + ": " +
                                   ec.message());
        u->port = u->sock.local_endpoint().port();
        m.udp.push_back(std::move(u));
      }
      m.bound_port = m.udp.front()->port;
      m.fanout.emplace(m.device.udp_traits(),
                       m.cfg.reply_port.value_or(top::client_port(m.cfg.model)));
      if (m.fanout->traits().ephemeral_reply_port) {
        // A port of its own, as a real Topotek camera's (sim/fanout.hpp);
        // it serves nothing.
        m.reply_sock = std::make_unique<Impl::UdpPort>(m.io);
        asio::ip::udp::endpoint ep(addr, 0);
        m.reply_sock->sock.open(ep.protocol(), ec);
        if (!ec) m.reply_sock->sock.bind(ep, ec);
        if (ec) throw std::runtime_error("udp " + m.cfg.host + ": reply port: " + ec.message());
        m.reply_sock->port = m.reply_sock->sock.local_endpoint().port();
      }
      for (auto& u : m.udp) m.udp_receive(*u);
      break;
    }
    case TransportKind::tcp: {
      auto addr = asio::ip::make_address(m.cfg.host, ec);
      if (ec) throw std::runtime_error("tcp: bad host '" + m.cfg.host + "': " + ec.message());
      asio::ip::tcp::endpoint ep(addr, m.cfg.port);
      m.acceptor.emplace(m.io);
      m.acceptor->open(ep.protocol(), ec);
      if (!ec) m.acceptor->set_option(asio::socket_base::reuse_address(true), ec);
      if (!ec) m.acceptor->bind(ep, ec);
      if (!ec) m.acceptor->listen(asio::socket_base::max_listen_connections, ec);
      if (ec)
        throw std::runtime_error("tcp " + m.cfg.host + ":" + std::to_string(m.cfg.port) + ": " +
                                 ec.message());
      m.bound_port = m.acceptor->local_endpoint().port();
      m.tcp_accept();
      break;
    }
    case TransportKind::pty: {
      int master = -1, slave = -1;
      char name[256] = {0};
      if (openpty(&master, &slave, name, nullptr, nullptr) != 0)
        throw std::runtime_error(std::string("openpty: ") + std::strerror(errno));
      termios t{};
      if (tcgetattr(slave, &t) == 0) {
        cfmakeraw(&t);
        tcsetattr(slave, TCSANOW, &t);
      }
      m.pty_slave = slave;  // kept open so the master never sees EIO/HUP
      m.pty_path = name;
      ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
      m.pty_line = std::make_shared<Impl::PtyLine>(asio::posix::stream_descriptor(m.io, master));
      m.line_read(m.pty_line);
      break;
    }
    case TransportKind::serial: {
      asio::serial_port sp(m.io);
      sp.open(m.cfg.device, ec);
      if (ec) throw std::runtime_error("serial " + m.cfg.device + ": " + ec.message());
      sp.set_option(asio::serial_port::baud_rate(m.cfg.baud), ec);
      sp.set_option(asio::serial_port::character_size(8), ec);
      sp.set_option(asio::serial_port::parity(asio::serial_port::parity::none), ec);
      sp.set_option(asio::serial_port::stop_bits(asio::serial_port::stop_bits::one), ec);
      m.serial_line = std::make_shared<Impl::SerialLine>(std::move(sp));
      m.line_read(m.serial_line);
      break;
    }
  }
  m.arm_reboot();
}

Server::~Server() {
  if (impl_ && impl_->pty_slave >= 0) ::close(impl_->pty_slave);
}

std::uint16_t Server::port() const noexcept { return impl_->bound_port; }

std::vector<std::uint16_t> Server::udp_ports() const {
  std::vector<std::uint16_t> out;
  for (const auto& u : impl_->udp) out.push_back(u->port);
  return out;
}

std::uint16_t Server::reply_from_port() const noexcept {
  return impl_->reply_sock ? impl_->reply_sock->port : 0;
}

std::uint16_t Server::client_port() const noexcept {
  return impl_->fanout ? impl_->fanout->client_port() : 0;
}

UdpTraits Server::udp_traits() const noexcept {
  return impl_->fanout ? impl_->fanout->traits() : UdpTraits{};
}

void Server::stop_on_signals() {
  auto sig = std::make_shared<asio::signal_set>(impl_->io, SIGINT, SIGTERM);
  sig->async_wait([this, sig](std::error_code ec, int) {
    if (!ec) impl_->io.stop();
  });
}
void Server::restart_on_hangup() {
  impl_->wait_hangup(std::make_shared<asio::signal_set>(impl_->io, SIGHUP));
}

void Server::restart() {
  asio::post(impl_->io, [this] { impl_->restart(); });
}

std::string Server::pty_path() const { return impl_->pty_path; }
const ServerStats& Server::stats() const noexcept { return impl_->stats; }

void Server::run() {
  auto guard = asio::make_work_guard(impl_->io);
  impl_->io.run();
  if (impl_->pcap) impl_->pcap->flush();
}

void Server::stop() { impl_->io.stop(); }

}  // namespace topsim
