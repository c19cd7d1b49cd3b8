// A topsim server running on its own thread for the length of a test.
#pragma once

#include <thread>

#include "sim/server.hpp"

struct RunningServer {
  explicit RunningServer(topsim::ServerConfig cfg) : server(std::move(cfg)) {
    thread = std::thread([this] { server.run(); });
  }
  ~RunningServer() {
    server.stop();
    thread.join();
  }
  topsim::Server server;
  std::thread thread;
};
