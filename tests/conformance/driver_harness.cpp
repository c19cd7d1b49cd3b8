#include "driver_harness.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <nlohmann/json.hpp>

namespace {

std::uint64_t steady_us() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                        std::chrono::steady_clock::now().time_since_epoch())
                                        .count());
}

sockaddr_in address(const std::string& host, std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  ::inet_pton(AF_INET, host.c_str(), &a.sin_addr);
  return a;
}

// A client's UDP socket as a public client opens it (UdpClient).
class ClientSocket : public topconf::Transport {
 public:
  ClientSocket(UdpClient how, const std::string& host, std::uint16_t port, top::Model model)
      : how_(how), model_(model), peer_(address(host, port)) {
    send_fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    const sockaddr_in any = address(host, 0);
    if (how == UdpClient::connected) {
      // bound to the host's address, then connect()ed, as a SocketAPM is
      ::bind(send_fd_, reinterpret_cast<const sockaddr*>(&any), sizeof any);
      if (::connect(send_fd_, reinterpret_cast<const sockaddr*>(&peer_), sizeof peer_) != 0)
        throw topconf::TransportError("connect: " + std::string(std::strerror(errno)));
      recv_fd_ = send_fd_;
      return;
    }
    // PixEagle: the control socket is never bound by hand (its first
    // sendto() picks a port; here the host's address), the listener is
    // bound to the client port with SO_REUSEADDR.
    ::bind(send_fd_, reinterpret_cast<const sockaddr*>(&any), sizeof any);
    recv_fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    const int one = 1;
    ::setsockopt(recv_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    const sockaddr_in listen = address(host, top::client_port(model));
    if (::bind(recv_fd_, reinterpret_cast<const sockaddr*>(&listen), sizeof listen) != 0)
      throw topconf::TransportError("bind " + host + ":" + std::to_string(top::client_port(model)) +
                                    ": " + std::strerror(errno));
  }
  ~ClientSocket() override {
    if (recv_fd_ != send_fd_) ::close(recv_fd_);
    ::close(send_fd_);
  }
  std::uint64_t now_us() override { return steady_us(); }
  bool datagram() const override { return true; }
  char client_address() const override {
    return top::client_address(top::dialect_of(model_), top::Link::network);
  }
  void send(std::string_view b) override {
    if (how_ == UdpClient::connected)
      ::send(send_fd_, b.data(), b.size(), 0);
    else
      ::sendto(send_fd_, b.data(), b.size(), 0, reinterpret_cast<const sockaddr*>(&peer_),
               sizeof peer_);
  }
  bool receive(std::uint64_t deadline_us, std::string& out) override {
    char buf[65536];
    for (;;) {
      const std::uint64_t now = steady_us();
      const int ms = now >= deadline_us ? 0 : static_cast<int>((deadline_us - now + 999) / 1000);
      pollfd p{recv_fd_, POLLIN, 0};
      if (::poll(&p, 1, ms) <= 0) return false;
      const ssize_t n = ::recv(recv_fd_, buf, sizeof buf, 0);
      if (n < 0) continue;  // ECONNREFUSED on the connected socket: nobody there yet
      out.assign(buf, static_cast<std::size_t>(n));
      return true;
    }
  }
  std::string describe() const override { return "a client's UDP socket"; }

 private:
  UdpClient how_;
  top::Model model_;
  sockaddr_in peer_;
  int send_fd_ = -1, recv_fd_ = -1;
};

int rank(const std::string& severity) {
  return severity == "error" ? 2 : severity == "warning" ? 1 : 0;
}

std::string text(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

std::unique_ptr<topconf::Transport> open_udp_client(UdpClient how, const std::string& host,
                                                    std::uint16_t port, top::Model model) {
  if (how == UdpClient::unconnected)
    return topconf::open_transport("udp://" + host + ":" + std::to_string(port), model, 0);
  return std::make_unique<ClientSocket>(how, host, port, model);
}

JsonLines topdump_read_json(const std::string& pcap) { return topdump_read_json(pcap, {}); }

JsonLines topdump_read_json(const std::string& pcap, const std::string& args) {
  JsonLines r;
  const std::string cmd = "'" + std::string(TOPKIT_BINARY_DIR) + "/analyzer/topdump' read --json " +
                          args + " '" + pcap + "'";
  FILE* f = ::popen(cmd.c_str(), "r");
  if (!f) return r;
  std::string out;
  char buf[65536];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
  const int st = ::pclose(f);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  for (std::size_t start = 0; start < out.size();) {
    const std::size_t end = std::min(out.find('\n', start), out.size());
    std::string line = out.substr(start, end - start);
    auto j = nlohmann::json::parse(line, nullptr, false);
    r.lines.emplace_back(std::move(line), std::move(j));
    start = end + 1;
  }
  return r;
}

Dump topdump_findings(const std::string& pcap, const std::string& min_severity,
                      const std::string& args) {
  Dump d;
  const JsonLines run = topdump_read_json(pcap, args);
  d.status = run.status;
  const int floor = rank(min_severity);
  for (const auto& [line, j] : run.lines) {
    ++d.lines;
    if (j.is_discarded()) {
      d.findings.push_back({"unparsable-json-line", "error", line.substr(0, 80), "", -1});
      continue;
    }
    const auto add = [&](const nlohmann::json& x, const std::string& ident, long long frame) {
      if (rank(text(x, "severity")) >= floor)
        d.findings.push_back(
            {text(x, "code"), text(x, "severity"), text(x, "message"), ident, frame});
    };
    if (text(j, "type") == "finding") {
      add(j, "", j.value("frame", nlohmann::json()).is_number() ? j["frame"].get<long long>() : -1);
    } else {
      // A frame's own findings and the session's notes on it (unsolicited...).
      const long long at =
          j.value("n", nlohmann::json()).is_number() ? j["n"].get<long long>() : -1;
      for (const char* key : {"findings", "session"})
        if (j.contains(key) && j[key].is_array())
          for (const auto& x : j[key])
            if (x.is_object()) add(x, text(j, "ident"), at);
    }
  }
  return d;
}

std::string describe(const Dump& d) {
  std::string s = "topdump exit " + std::to_string(d.status) + ", " +
                  std::to_string(d.findings.size()) + " finding(s):\n";
  std::size_t shown = 0;
  for (const DumpFinding& f : d.findings) {
    if (++shown > 40) {
      s += "  ...\n";
      break;
    }
    s += "  " + f.code + " (" + f.ident + ", frame " + std::to_string(f.frame) + "): " + f.message +
         "\n";
  }
  return s;
}
