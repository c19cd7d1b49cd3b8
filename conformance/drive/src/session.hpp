// What a case's run shares with the persistent mode (private to drive/):
// the beliefs reader, the truth sampler, the device's server, the
// intents file and topdump's diagnoses of the capture.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "drive/runner.hpp"
#include "sim/server.hpp"
#include "wire.hpp"

namespace topconf::drive::detail {

using Steady = std::chrono::steady_clock;

// The driver's stdout: belief lines stamped with their receipt time
// (seconds since `t0`). Thread-safe.
class BeliefLog {
 public:
  void take(Steady::time_point t0, Steady::time_point at, const std::string& line);
  // The beliefs in [from, to) seconds, re-stamped from `from`; the non-JSON
  // lines and error texts among them counted into `r`.
  void slice(double from, double to, Record& r) const;

 private:
  mutable std::mutex mu_;
  struct Line {
    double t;
    bool json;
    nlohmann::json j;
  };
  std::vector<Line> lines_;
};

// A device served on its own thread, its wire tapped (times in seconds
// since the driver started: set_t0 once it has).
class DeviceRun {
 public:
  DeviceRun(const DriveOptions& o, const CaseSetup& s, const std::string& capture);
  ~DeviceRun();
  topsim::Server& server() { return *server_; }
  void set_t0(Steady::time_point t0) { t0_ns_ = t0.time_since_epoch().count(); }
  // The command's placeholders and the environment of the link.
  std::vector<std::pair<std::string, std::string>> link_values() const;
  // One truth sample now (false when the server did not answer).
  bool sample(std::vector<Truth>& out, double t);
  // The device's identity and range as it answers them.
  void identity(Record& r);
  std::vector<WireFrame> frames() const { return tap_.frames(); }
  // Stops the server and closes its capture.
  void stop();

 private:
  top::Model model_;
  WireTap tap_;
  std::atomic<Steady::rep> t0_ns_{0};
  std::unique_ptr<topsim::Server> server_;
  std::thread thread_;
  topsim::TransportKind kind_;
};

// Writes `intents` as JSON Lines to `path` (appending when `append`), each
// `t` moved by `offset` seconds; throws std::runtime_error naming the file.
void write_intents(const std::string& path, const std::vector<Intent>& intents, double offset,
                   bool append, const nlohmann::json* header = nullptr);

// topdump's diagnoses of a capture (`topdump read --json`), or a note why
// there are none.
std::vector<Diagnosis> diagnose(const std::string& topdump, top::Model model,
                                const std::string& capture, std::string& note);
// The topdump to run: `given`, else next to this program, in ../analyzer/,
// then "topdump" (PATH).
std::string find_topdump(const std::string& given);

// The capture's file name for a link: wire.pcap, or wire.log on a pty.
std::string capture_name(topsim::TransportKind k);

}  // namespace topconf::drive::detail
