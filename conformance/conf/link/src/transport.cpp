#include "conf/transport.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <asio.hpp>
#include <chrono>
#include <ctime>
#include <type_traits>

#include "top/device.hpp"
#include "top/dialect.hpp"

namespace topconf {

// Asio transports: sockets and a serial port, waited on with poll(2) so a
// deadline always ends a wait.

namespace {

using SteadyClock = std::chrono::steady_clock;

std::uint64_t steady_us() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(SteadyClock::now().time_since_epoch())
          .count());
}

bool wait_readable(int fd, std::uint64_t deadline_us) {
  for (;;) {
    const std::uint64_t now = steady_us();
    if (now >= deadline_us) {
      pollfd p{fd, POLLIN, 0};
      return ::poll(&p, 1, 0) > 0;
    }
    const std::uint64_t left = deadline_us - now;
    timespec ts{static_cast<time_t>(left / 1000000), static_cast<long>((left % 1000000) * 1000)};
    pollfd p{fd, POLLIN, 0};
    const int r = ::ppoll(&p, 1, &ts, nullptr);
    if (r > 0) return true;
    if (r == 0) return false;
    if (errno != EINTR) throw TransportError(std::string("poll: ") + std::strerror(errno));
  }
}

bool split_host_port(const std::string& s, std::string& host, std::uint16_t& port) {
  const auto colon = s.rfind(':');
  if (colon == std::string::npos || colon == 0) return false;
  host = s.substr(0, colon);
  try {
    std::size_t used = 0;
    const unsigned long p = std::stoul(s.substr(colon + 1), &used);
    if (used != s.size() - colon - 1 || p == 0 || p > 65535) return false;
    port = static_cast<std::uint16_t>(p);
  } catch (...) {
    return false;
  }
  return true;
}

char client_for(top::Model m, bool network) {
  return top::client_address(top::dialect_of(m), network ? top::Link::network : topsim::Link::uart);
}

// The endpoints a pcap names for a socket: loopback with the socket's own
// port, and the peer (loopback for one that is not IPv4).
template <class Socket>
pcapio::Endpoint local_of(const Socket& sock) {
  std::error_code ec;
  auto e = sock.local_endpoint(ec);
  return pcapio::Endpoint::ipv4(0x7F000001u, ec ? std::uint16_t{0} : e.port());
}

template <class Peer>
pcapio::Endpoint remote_of(const Peer& peer) {
  return pcapio::Endpoint::ipv4(
      peer.address().is_v4() ? peer.address().to_v4().to_uint() : 0x7F000001u, peer.port());
}

// What the transports to a real device share: an asio object (socket,
// serial port) on an io_context of its own, the wall clock, and the client
// address the model's dialect uses on a network or a serial link.
template <class Handle>
class AsioTransport : public Transport {
 public:
  std::uint64_t now_us() override { return steady_us(); }
  char client_address() const override { return client_for(model_, network_); }
  bool datagram() const override { return std::is_same_v<Handle, asio::ip::udp::socket>; }

 protected:
  AsioTransport(top::Model model, bool network) : handle_(io_), model_(model), network_(network) {}
  // Writes all of `b` to a byte stream (TCP, serial); TransportError
  // "`what`: ..." on failure.
  void write_all(std::string_view b, const char* what) {
    std::error_code ec;
    asio::write(handle_, asio::buffer(b.data(), b.size()), ec);
    if (ec) throw TransportError(std::string(what) + ": " + ec.message());
  }

  asio::io_context io_;
  Handle handle_;
  top::Model model_;
  bool network_;
};

class UdpTransport : public AsioTransport<asio::ip::udp::socket> {
 public:
  UdpTransport(const std::string& host, std::uint16_t port, top::Model model, int local_port)
      : AsioTransport(model, true) {
    std::error_code ec;
    auto addr = asio::ip::make_address(host, ec);
    if (ec) throw TransportError("udp://" + host + ": not an IP address");
    peer_ = asio::ip::udp::endpoint(addr, port);
    handle_.open(peer_.protocol(), ec);
    // A fixed port (Topotek 9004) may be bound by another client of the
    // device on this host too, as PixEagle's listener does.
    if (!ec && local_port > 0) handle_.set_option(asio::socket_base::reuse_address(true), ec);
    const asio::ip::address any = addr.is_v6() ? asio::ip::address(asio::ip::address_v6::any())
                                               : asio::ip::address(asio::ip::address_v4::any());
    if (!ec)
      handle_.bind(asio::ip::udp::endpoint(addr.is_loopback() ? addr : any,
                                           static_cast<std::uint16_t>(std::max(local_port, 0))),
                   ec);
    if (ec)
      throw TransportError("udp://" + host + ":" + std::to_string(port) +
                           (local_port > 0 ? ": bind port " + std::to_string(local_port) : "") +
                           ": " + ec.message());
    // The kernel's arrival time of each datagram (arrived_us).
    const int on = 1;
    ::setsockopt(handle_.native_handle(), SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
    handle_.non_blocking(true, ec);
  }
  void send(std::string_view b) override {
    std::error_code ec;
    handle_.send_to(asio::buffer(b.data(), b.size()), peer_, 0, ec);
    if (ec && ec != asio::error::connection_refused)
      throw TransportError("udp send: " + ec.message());
  }
  bool receive(std::uint64_t deadline_us, std::string& out) override {
    char buf[65536];
    for (;;) {
      if (!wait_readable(handle_.native_handle(), deadline_us)) return false;
      sockaddr_storage from{};
      iovec iov{buf, sizeof buf};
      alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec))];
      msghdr msg{};
      msg.msg_name = &from;
      msg.msg_namelen = sizeof from;
      msg.msg_iov = &iov;
      msg.msg_iovlen = 1;
      msg.msg_control = control;
      msg.msg_controllen = sizeof control;
      const ssize_t n = ::recvmsg(handle_.native_handle(), &msg, 0);
      const std::uint64_t now = steady_us();
      if (n < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) continue;
        // ICMP port unreachable (Linux reports it on unconnected sockets
        // too, now and then): nobody listens yet; wait until the deadline.
        if (errno == ECONNREFUSED) {
          if (now >= deadline_us) return false;
          continue;
        }
        throw TransportError(std::string("udp receive: ") + std::strerror(errno));
      }
      // What another host sends is not the device's.
      if (!from_peer_host(from)) continue;
      arrived_ = now;
      for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
          timespec at{}, wall{};
          std::memcpy(&at, CMSG_DATA(c), sizeof at);
          ::clock_gettime(CLOCK_REALTIME, &wall);
          const std::int64_t ago = (static_cast<std::int64_t>(wall.tv_sec) - at.tv_sec) * 1000000 +
                                   (wall.tv_nsec - at.tv_nsec) / 1000;
          if (ago > 0 && static_cast<std::uint64_t>(ago) < now)
            arrived_ = now - static_cast<std::uint64_t>(ago);
        }
      out.assign(buf, static_cast<std::size_t>(n));
      return true;
    }
  }
  std::uint64_t arrived_us() override { return arrived_; }
  pcapio::Endpoint local() const override { return local_of(handle_); }
  pcapio::Endpoint remote() const override { return remote_of(peer_); }
  std::string describe() const override {
    return "udp://" + peer_.address().to_string() + ":" + std::to_string(peer_.port());
  }

 private:
  bool from_peer_host(const sockaddr_storage& from) const {
    const asio::ip::address a = peer_.address();
    if (from.ss_family == AF_INET && a.is_v4()) {
      const auto& in = reinterpret_cast<const sockaddr_in&>(from);
      return ntohl(in.sin_addr.s_addr) == a.to_v4().to_uint();
    }
    if (from.ss_family == AF_INET6 && a.is_v6()) {
      const auto& in6 = reinterpret_cast<const sockaddr_in6&>(from);
      return std::memcmp(in6.sin6_addr.s6_addr, a.to_v6().to_bytes().data(), 16) == 0;
    }
    return false;
  }
  asio::ip::udp::endpoint peer_;
  std::uint64_t arrived_ = 0;
};

class TcpTransport : public AsioTransport<asio::ip::tcp::socket> {
 public:
  TcpTransport(const std::string& host, std::uint16_t port, top::Model model)
      : AsioTransport(model, true) {
    std::error_code ec;
    auto addr = asio::ip::make_address(host, ec);
    if (ec) throw TransportError("tcp://" + host + ": not an IP address");
    peer_ = asio::ip::tcp::endpoint(addr, port);
    handle_.connect(peer_, ec);
    if (ec)
      throw TransportError("tcp://" + host + ":" + std::to_string(port) + ": " + ec.message());
    handle_.set_option(asio::ip::tcp::no_delay(true), ec);
  }
  void send(std::string_view b) override { write_all(b, "tcp send"); }
  bool receive(std::uint64_t deadline_us, std::string& out) override {
    if (!wait_readable(handle_.native_handle(), deadline_us)) return false;
    char buf[4096];
    std::error_code ec;
    const std::size_t n = handle_.read_some(asio::buffer(buf), ec);
    if (ec)
      throw TransportError("tcp receive: " + (ec == asio::error::eof
                                                  ? std::string("connection closed by the device")
                                                  : ec.message()));
    out.assign(buf, n);
    return true;
  }
  pcapio::Endpoint local() const override { return local_of(handle_); }
  pcapio::Endpoint remote() const override { return remote_of(peer_); }
  bool tcp() const override { return true; }
  std::string describe() const override {
    return "tcp://" + peer_.address().to_string() + ":" + std::to_string(peer_.port());
  }

 private:
  asio::ip::tcp::endpoint peer_;
};

class SerialTransport : public AsioTransport<asio::serial_port> {
 public:
  SerialTransport(const std::string& dev, unsigned baud, top::Model model)
      : AsioTransport(model, false), dev_(dev) {
    std::error_code ec;
    handle_.open(dev, ec);
    if (ec) throw TransportError("serial:" + dev + ": " + ec.message());
    handle_.set_option(asio::serial_port::baud_rate(baud), ec);
    if (ec)
      throw TransportError("serial:" + dev + ": baud " + std::to_string(baud) + ": " +
                           ec.message());
    handle_.set_option(asio::serial_port::character_size(8), ec);
    handle_.set_option(asio::serial_port::parity(asio::serial_port::parity::none), ec);
    handle_.set_option(asio::serial_port::stop_bits(asio::serial_port::stop_bits::one), ec);
    handle_.set_option(asio::serial_port::flow_control(asio::serial_port::flow_control::none), ec);
  }
  void send(std::string_view b) override { write_all(b, "serial write"); }
  bool receive(std::uint64_t deadline_us, std::string& out) override {
    if (!wait_readable(handle_.native_handle(), deadline_us)) return false;
    char buf[4096];
    const ssize_t n = ::read(handle_.native_handle(), buf, sizeof buf);
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) return false;
      throw TransportError("serial read: " + std::string(std::strerror(errno)));
    }
    if (n == 0) return false;
    out.assign(buf, static_cast<std::size_t>(n));
    return true;
  }
  pcapio::Endpoint local() const override { return pcapio::Endpoint::ipv4(0x7F000001u, 9001); }
  pcapio::Endpoint remote() const override { return pcapio::Endpoint::ipv4(0x7F000001u, 9000); }
  std::string describe() const override { return "serial:" + dev_; }

 private:
  std::string dev_;
};

}  // namespace

std::unique_ptr<Transport> open_transport(const std::string& target, top::Model model,
                                          int local_port) {
  std::string host;
  std::uint16_t port = 0;
  if (target.rfind("udp://", 0) == 0) {
    if (!split_host_port(target.substr(6), host, port))
      throw TransportError(target + ": expected udp://HOST:PORT");
    return std::make_unique<UdpTransport>(host, port, model, local_port);
  }
  if (target.rfind("tcp://", 0) == 0) {
    if (!split_host_port(target.substr(6), host, port))
      throw TransportError(target + ": expected tcp://HOST:PORT");
    return std::make_unique<TcpTransport>(host, port, model);
  }
  if (target.rfind("serial:", 0) == 0) {
    std::string dev = target.substr(7);
    unsigned baud = 115200;
    if (auto at = dev.rfind('@'); at != std::string::npos) {
      try {
        baud = static_cast<unsigned>(std::stoul(dev.substr(at + 1)));
      } catch (...) {
        throw TransportError(target + ": bad baud rate");
      }
      dev = dev.substr(0, at);
    }
    if (dev.empty()) throw TransportError(target + ": expected serial:DEVICE[@BAUD]");
    return std::make_unique<SerialTransport>(dev, baud, model);
  }
  throw TransportError(target +
                       ": expected udp://HOST:PORT, tcp://HOST:PORT or serial:DEVICE[@BAUD]");
}

std::unique_ptr<Transport> open_target(bool sim, const std::string& target, top::Model model,
                                       const std::string& sim_faults, std::uint64_t sim_seed,
                                       int bind_port, topsim::Link sim_link) {
  if (sim) {
    topsim::FaultConfig fc;
    if (!sim_faults.empty()) {
      std::string err;
      auto f = topsim::parse_faults(sim_faults, err);
      if (!f) throw TransportError("--sim-fault: " + err);
      fc = *f;
    }
    return std::make_unique<SimTransport>(model, fc, sim_seed, sim_link);
  }
  int local = bind_port;
  if (local < 0 && top::client_port(model) && target.rfind("udp://", 0) == 0)
    local = top::client_port(model);
  return open_transport(target, model, local);
}

}  // namespace topconf
