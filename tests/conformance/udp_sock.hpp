// A client's UDP socket for tests against topsim over real UDP: bound on a
// loopback host of the test's own (loopback.hpp), it sends frames with
// their checksum and collects what arrives, with the sender's port.
#pragma once

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "top/frame.hpp"

struct Datagram {
  std::string bytes;
  std::uint16_t from = 0;  // the sender's port
};

// A client's UDP socket on `host` (port 0: ephemeral), SO_REUSEADDR as
// PixEagle's 9004 listener.
class Sock {
 public:
  Sock(const std::string& host, std::uint16_t port = 0) : host_(host) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    const int one = 1;
    ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a = addr(host, port);
    ok = ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    socklen_t len = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  ~Sock() { ::close(fd_); }
  Sock(const Sock&) = delete;
  Sock& operator=(const Sock&) = delete;
  bool ok = false;
  std::uint16_t port() const { return port_; }

  void send(std::string_view body, std::uint16_t to) const {
    const std::string f = top::with_checksum(body);
    sockaddr_in a = addr(host_, to);
    ::sendto(fd_, f.data(), f.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
  }
  // The datagrams that came until one satisfies `done` (kept), within 3 s.
  std::vector<Datagram> until(const std::function<bool(const Datagram&)>& done) {
    std::vector<Datagram> got;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      got.push_back(take());
      if (done(got.back())) return got;
    }
    ADD_FAILURE() << "port " << port_ << ": the awaited datagram did not come";
    return got;
  }
  // Datagrams of `ident` until the `n`th one.
  std::vector<Datagram> until_n(std::string_view ident, std::size_t n) {
    std::size_t seen = 0;
    return until([&](const Datagram& d) { return ident_of(d) == ident && ++seen == n; });
  }
  // What is queued now, without waiting.
  std::vector<Datagram> queued() {
    std::vector<Datagram> got;
    for (;;) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 0) <= 0) return got;
      got.push_back(take());
    }
  }
  static std::string ident_of(const Datagram& d) {
    const top::ParseResult r = top::parse_exact(d.bytes);
    return r.status == top::ParseStatus::frame ? std::string(r.frame.ident_view()) : "";
  }

 private:
  static sockaddr_in addr(const std::string& host, std::uint16_t port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    ::inet_pton(AF_INET, host.c_str(), &a.sin_addr);
    return a;
  }
  Datagram take() {
    char buf[2048];
    sockaddr_in from{};
    socklen_t len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buf, sizeof buf, 0, reinterpret_cast<sockaddr*>(&from), &len);
    return Datagram{std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0),
                    ntohs(from.sin_port)};
  }
  std::string host_;
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

inline std::size_t count(const std::vector<Datagram>& v, std::string_view ident) {
  std::size_t n = 0;
  for (const Datagram& d : v) n += Sock::ident_of(d) == ident;
  return n;
}
