// The driver under test as a process (private to drive/): started through
// /bin/sh -c in its own process group, its stdout read line by line, its
// stderr in a file; stopped with SIGTERM, then SIGKILL.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace topconf::drive::detail {

// Replaces {name} in `command` by each value (h2spec's --exec style).
std::string substitute(std::string command,
                       const std::vector<std::pair<std::string, std::string>>& values);

class DriverProcess {
 public:
  using Line = std::function<void(std::chrono::steady_clock::time_point, std::string)>;
  // Starts `/bin/sh -c command` in `dir` with `env` added to topconf's own
  // environment; each stdout line goes to `on_line` (from a reader thread).
  // Throws std::runtime_error naming what failed.
  DriverProcess(const std::string& command, const std::string& dir,
                const std::vector<std::pair<std::string, std::string>>& env,
                const std::string& stderr_path, Line on_line);
  ~DriverProcess();
  DriverProcess(const DriverProcess&) = delete;
  DriverProcess& operator=(const DriverProcess&) = delete;

  std::chrono::steady_clock::time_point started() const { return started_; }
  // Whether it has exited (reaps it): its status text then.
  bool exited();
  // "exit 0", "exit 127", "signal 15"; empty while it runs.
  const std::string& status() const { return status_; }
  int exit_code() const { return code_; }  // -1 unless it exited normally
  // SIGTERM to its process group, SIGKILL 1 s later if still there; waits
  // for the stdout reader. Returns how it ended.
  std::string stop();

 private:
  void reap(int st);
  pid_t pid_ = -1;
  int out_ = -1;
  std::chrono::steady_clock::time_point started_;
  std::string status_;
  int code_ = -1;
  std::atomic<bool> closing_{false};
  std::thread reader_;
};

}  // namespace topconf::drive::detail
