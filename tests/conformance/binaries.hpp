// Running the built binaries from a test: topsim in the background (its
// pid and the address it prints), and a command's exit status.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

inline std::string bin(const char* name) {
  return std::string(TOPKIT_BINARY_DIR) + "/conformance/" + name;
}

// Starts topsim and returns its pid and the first line it prints.
inline pid_t start_topsim(const std::vector<std::string>& args, std::string& line) {
  int fds[2];
  if (pipe(fds) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], 1);
    close(fds[0]);
    std::vector<char*> argv;
    std::string exe = bin("topsim");
    argv.push_back(exe.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  close(fds[1]);
  char c;
  line.clear();
  while (read(fds[0], &c, 1) == 1 && c != '\n') line.push_back(c);
  close(fds[0]);
  return pid;
}

inline int run_cmd(const std::string& cmd) {
  const int rc = std::system((cmd + " >/dev/null 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}
