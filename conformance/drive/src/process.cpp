#include "process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace topconf::drive::detail {

std::string substitute(std::string command,
                       const std::vector<std::pair<std::string, std::string>>& values) {
  for (const auto& [name, value] : values) {
    const std::string key = "{" + name + "}";
    for (std::size_t at = command.find(key); at != std::string::npos;
         at = command.find(key, at + value.size()))
      command.replace(at, key.size(), value);
  }
  return command;
}

DriverProcess::DriverProcess(const std::string& command, const std::string& dir,
                             const std::vector<std::pair<std::string, std::string>>& env,
                             const std::string& stderr_path, Line on_line) {
  int pipefd[2];
  if (::pipe2(pipefd, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  // The environment: topconf's, with the case's variables replacing any
  // of the same name.
  std::vector<std::string> vars;
  for (char** e = environ; *e; ++e) {
    const std::string v(*e);
    bool ours = false;
    for (const auto& [k, val] : env) ours = ours || v.compare(0, k.size() + 1, k + "=") == 0;
    if (!ours) vars.push_back(v);
  }
  for (const auto& [k, val] : env) vars.push_back(k + "=" + val);
  std::vector<char*> envp;
  for (std::string& v : vars) envp.push_back(v.data());
  envp.push_back(nullptr);
  std::string sh = "/bin/sh", dash_c = "-c", cmd = command;
  char* argv[] = {sh.data(), dash_c.data(), cmd.data(), nullptr};

  posix_spawn_file_actions_t fa;
  posix_spawnattr_t attr;
  posix_spawn_file_actions_init(&fa);
  posix_spawnattr_init(&attr);
  posix_spawn_file_actions_adddup2(&fa, pipefd[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, stderr_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addchdir_np(&fa, dir.c_str());
  posix_spawnattr_setpgroup(&attr, 0);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  sigset_t dfl;
  sigemptyset(&dfl);
  sigaddset(&dfl, SIGTERM);
  sigaddset(&dfl, SIGINT);
  sigaddset(&dfl, SIGPIPE);
  posix_spawnattr_setsigdefault(&attr, &dfl);
  posix_spawnattr_setflags(&attr,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  started_ = std::chrono::steady_clock::now();
  const int rc = ::posix_spawn(&pid_, sh.c_str(), &fa, &attr, argv, envp.data());
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  ::close(pipefd[1]);
  if (rc != 0) {
    ::close(pipefd[0]);
    pid_ = -1;
    throw std::runtime_error("cannot start /bin/sh -c '" + command + "': " + std::strerror(rc));
  }
  out_ = pipefd[0];
  reader_ = std::thread([this, fd = out_, on_line = std::move(on_line)] {
    std::string buf;
    char chunk[4096];
    for (;;) {
      // Polled, so that a stop ends the reader even when something outside
      // the process group still holds the pipe.
      pollfd p{fd, POLLIN, 0};
      const int ready = ::poll(&p, 1, 100);
      if (ready == 0) {
        if (closing_) break;
        continue;
      }
      if (ready < 0 && errno == EINTR) continue;
      const ssize_t n = ::read(fd, chunk, sizeof chunk);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      const auto now = std::chrono::steady_clock::now();
      buf.append(chunk, static_cast<std::size_t>(n));
      for (std::size_t nl; (nl = buf.find('\n')) != std::string::npos;) {
        on_line(now, buf.substr(0, nl));
        buf.erase(0, nl + 1);
      }
      // A line without its end past 64 KiB is cut there (bounded memory).
      if (buf.size() > 65536) {
        on_line(now, buf);
        buf.clear();
      }
    }
    if (!buf.empty()) on_line(std::chrono::steady_clock::now(), buf);
  });
}

void DriverProcess::reap(int st) {
  if (WIFEXITED(st)) {
    code_ = WEXITSTATUS(st);
    status_ = "exit " + std::to_string(code_);
  } else if (WIFSIGNALED(st)) {
    status_ = "signal " + std::to_string(WTERMSIG(st));
  }
  pid_ = -1;
}

bool DriverProcess::exited() {
  if (pid_ < 0) return true;
  int st = 0;
  const pid_t r = ::waitpid(pid_, &st, WNOHANG);
  if (r == pid_) reap(st);
  return pid_ < 0;
}

std::string DriverProcess::stop() {
  if (pid_ > 0) {
    const pid_t pgid = pid_;
    ::kill(-pgid, SIGTERM);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (!exited() && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (pid_ > 0) {
      ::kill(-pgid, SIGKILL);
      int st = 0;
      if (::waitpid(pid_, &st, 0) == pid_) reap(st);
      status_ += " (SIGKILL after SIGTERM)";
    }
    // What the shell left in the group (a driver it forked) goes too.
    ::kill(-pgid, SIGKILL);
  }
  closing_ = true;
  if (reader_.joinable()) reader_.join();
  if (out_ >= 0) ::close(out_), out_ = -1;
  return status_;
}

DriverProcess::~DriverProcess() { stop(); }

}  // namespace topconf::drive::detail
