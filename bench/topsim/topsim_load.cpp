// topsim_load: requests per second topsim answers over UDP loopback, with
// the count of lost responses, against a floor measured in the same run (a
// plain UDP echo server on the same loopback, same client, same window).
//
//   topsim_load [--model c12] [--requests 200000] [--window 32] [--target HOST:PORT]
#include <poll.h>

#include <CLI/CLI.hpp>
#include <asio.hpp>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "sim/server.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Result {
  std::uint64_t sent = 0, received = 0, lost = 0;
  double seconds = 0;
};

// Sends `n` requests keeping `window` outstanding. A response that has not
// come 1 s after the last progress is counted lost, and the window reopens.
Result drive(const asio::ip::udp::endpoint& to, const std::string& req, std::uint64_t n,
             std::uint64_t window) {
  asio::io_context io;
  asio::ip::udp::socket s(io, asio::ip::udp::endpoint(asio::ip::address_v4::loopback(), 0));
  s.connect(to);
  s.set_option(asio::socket_base::receive_buffer_size(1 << 20));
  s.non_blocking(true);
  Result r;
  char buf[2048];
  const auto t0 = Clock::now();
  auto last_progress = Clock::now();
  while (r.received + r.lost < n) {
    while (r.sent < n && r.sent - r.received - r.lost < window) {
      std::error_code ec;
      s.send(asio::buffer(req), 0, ec);
      if (ec) break;
      ++r.sent;
    }
    pollfd p{s.native_handle(), POLLIN, 0};
    if (::poll(&p, 1, 50) > 0) {
      for (;;) {
        std::error_code ec;
        const std::size_t got = s.receive(asio::buffer(buf), 0, ec);
        if (ec) break;
        if (got > 0) ++r.received;
        last_progress = Clock::now();
      }
    } else if (Clock::now() - last_progress > std::chrono::seconds(1)) {
      r.lost = r.sent - r.received;
      last_progress = Clock::now();
    }
  }
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"topsim_load: topsim requests/s over UDP loopback, against a UDP echo floor"};
  std::string model = "c12", target;
  std::uint64_t requests = 200000, window = 32;
  bool json = false;
  app.add_option("--model", model)->capture_default_str();
  app.add_option("--requests", requests)->capture_default_str();
  app.add_option("--window", window, "requests in flight")->capture_default_str();
  app.add_option("--target", target,
                 "HOST:PORT of a running topsim (default: start one in process)");
  app.add_flag("--json", json, "one JSON object on stdout");
  CLI11_PARSE(app, argc, argv);
  auto m = top::model_from_string(model);
  if (!m || *m == top::Model::unknown) return 2;
  const bool topotek = top::dialect_of(*m) == top::Dialect::topotek;
  // A read with data: decode, state lookup, build, checksum on every request.
  const std::string req = top::build_frame(
      {top::Header::fixed, topotek ? 'P' : 'U', topotek ? 'G' : 'D', 'r', "VER", "00"});

  // The floor: a UDP echo server with the same socket and thread layout.
  asio::io_context echo_io;
  asio::ip::udp::socket echo(echo_io, asio::ip::udp::endpoint(asio::ip::address_v4::loopback(), 0));
  std::atomic<bool> stop{false};
  std::thread echo_thread([&] {
    char b[2048];
    echo.non_blocking(true);
    while (!stop) {
      pollfd p{echo.native_handle(), POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      for (;;) {
        asio::ip::udp::endpoint from;
        std::error_code ec;
        const std::size_t n = echo.receive_from(asio::buffer(b), from, 0, ec);
        if (ec) break;
        echo.send_to(asio::buffer(b, n), from, 0, ec);
      }
    }
  });
  const Result floor = drive(echo.local_endpoint(), req, requests, window);
  stop = true;
  echo_thread.join();

  std::unique_ptr<topsim::Server> server;
  std::thread sim_thread;
  asio::ip::udp::endpoint to;
  if (target.empty()) {
    topsim::ServerConfig cfg;
    cfg.model = *m;
    server = std::make_unique<topsim::Server>(cfg);
    sim_thread = std::thread([&] { server->run(); });
    to = asio::ip::udp::endpoint(asio::ip::address_v4::loopback(), server->port());
  } else {
    const auto colon = target.rfind(':');
    to = asio::ip::udp::endpoint(asio::ip::make_address(target.substr(0, colon)),
                                 static_cast<std::uint16_t>(std::stoul(target.substr(colon + 1))));
  }
  const Result sim = drive(to, req, requests, window);
  if (server) {
    server->stop();
    sim_thread.join();
  }
  const double sim_rps = static_cast<double>(sim.received) / sim.seconds;
  const double floor_rps = static_cast<double>(floor.received) / floor.seconds;
  const std::uint64_t lost = sim.lost;
  if (json) {
    std::printf(
        "{\"model\":\"%s\",\"requests\":%llu,\"responses\":%llu,\"lost\":%llu,\"seconds\":%.3f,"
        "\"requests_per_s\":%.0f,\"floor_echo_per_s\":%.0f,\"ratio_to_floor\":%.3f}\n",
        model.c_str(), static_cast<unsigned long long>(sim.sent),
        static_cast<unsigned long long>(sim.received), static_cast<unsigned long long>(lost),
        sim.seconds, sim_rps, floor_rps, sim_rps / floor_rps);
  } else {
    std::printf("topsim %s over UDP loopback: %llu requests, %llu responses, %llu lost, %.3f s\n",
                model.c_str(), static_cast<unsigned long long>(sim.sent),
                static_cast<unsigned long long>(sim.received),
                static_cast<unsigned long long>(lost), sim.seconds);
    std::printf(
        "  topsim     %10.0f requests/s\n  echo floor %10.0f requests/s\n  ratio      %10.3f\n",
        sim_rps, floor_rps, sim_rps / floor_rps);
  }
  return lost == 0 && sim_rps >= 10000 ? 0 : 1;
}
