// topkit_drive_client: a driver-like client for `topconf drive` (issue 50;
// docs/DRIVE.md). It speaks to a device over a
// pseudo-terminal, UDP or TCP as ArduPilot's Topotek driver (for the SIP)
// or SkyDroid driver (for the C12 and C13) does (topotek_client.hpp,
// driver_skydroid.hpp: one client with the in-process tests), performs
// the intents of TOPCONF_INTENT at their times, and prints what it
// believes as JSON Lines on stdout. --bug switches on a known driver bug
// (drive_client/drive_api.hpp). It stops cleanly on SIGTERM or SIGINT
// (exit 0), or after --duration.
//
// Exit status: 0 stopped; 1 the link failed; 2 bad usage, a bad intents
// file, or a failed write on stdout.
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "conf/link.hpp"
#include "conf/transport.hpp"
#include "drive_client/agent.hpp"
#include "drive_client/drive_api.hpp"
#include "driver_skydroid.hpp"
#include "topkit/cli.hpp"
#include "topotek_client.hpp"

namespace {

constexpr const char* kTool = "topkit_drive_client";
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

// How long ago this process started (its fork, /proc/self/stat field 22, in
// clock ticks since boot, against CLOCK_BOOTTIME): the intents' `t` counts
// from the driver's start, which topconf drive takes when it starts the
// command, so the time spent loading and opening the link here (hundreds
// of ms on a loaded machine) is not added to every intent. 0 when unknown.
std::uint64_t since_start_us() {
  std::FILE* f = std::fopen("/proc/self/stat", "r");
  if (!f) return 0;
  char buf[1024];
  const std::size_t n = std::fread(buf, 1, sizeof buf - 1, f);
  std::fclose(f);
  buf[n] = '\0';
  const char* p = std::strrchr(buf, ')');  // after the command name
  unsigned long long start = 0;
  if (!p || std::sscanf(p + 2,
                        "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %*u %*u %*d %*d %*d %*d "
                        "%*d %*d %llu",
                        &start) != 1)
    return 0;
  timespec now{};
  clock_gettime(CLOCK_BOOTTIME, &now);
  const double ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
  const double ago = static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) / 1e9 -
                     static_cast<double>(start) / ticks;
  return ago > 0 && ago < 10 ? static_cast<std::uint64_t>(ago * 1e6) : 0;
}

struct Options {
  std::string driver, pty, udp, tcp, intents, model;
  std::vector<std::string> bugs;
  double duration_s = 0;
  unsigned belief_ms = 200;
};

std::string bug_help() {
  std::string s = "a known driver bug to switch on (repeatable):";
  for (const drive::BugInfo& b : drive::bug_table())
    s += "\n  " + std::string(b.name) + " (fails " + std::string(b.cases) + "; " +
         (b.topotek && b.skydroid ? "both drivers"
          : b.topotek             ? "ardupilot-topotek"
                                  : "skydroid") +
         "): " + std::string(b.what);
  return s;
}

// Runs `c` on `t` until a signal or the duration: intents at their times
// (followed as the file grows with `follow`), beliefs at each new attitude
// and every belief_ms. Returns the exit status.
template <class Client>
int drive_loop(Client& c, topconf::Transport& t, const Options& o, drive::Script script,
               drive::IntentFile* follow) {
  c.client = t.client_address();
  topconf::FrameLink link(t, nullptr, 4096);
  // Time 0: TOPCONF_T0_US when topconf says it (CLOCK_MONOTONIC, the
  // steady clock of the link; docs/DRIVE.md), else this process's start.
  std::uint64_t start = link.now() - std::min(link.now(), since_start_us());
  if (const char* t0 = std::getenv("TOPCONF_T0_US")) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(t0, &end, 10);
    if (end && *end == '\0' && v > 0 && v <= link.now() && link.now() - v < 10000000) start = v;
  }
  const std::uint64_t end =
      o.duration_s > 0 ? start + static_cast<std::uint64_t>(o.duration_s * 1e6) : UINT64_MAX;
  std::uint64_t next_tick = start, next_belief = start, next_poll = start;
  std::size_t attitudes = 0;
  int skipped = 0;
  std::vector<std::string> out;
  for (std::uint64_t now = link.now(); !g_stop && now < end; now = link.now()) {
    if (follow && now >= next_poll) {
      next_poll = now + 100000;
      std::vector<drive::Intent> more;
      std::string why;
      if (!follow->poll(more, why)) {
        topkit::cli::error(kTool, why);
        return topkit::cli::close_stdout(kTool, 2);
      }
      script.add(more);
    }
    skipped += script.run_due(c, now - start, now);
    if (now >= next_tick) {
      out.clear();
      next_tick = c.tick(now, out);
      for (const std::string& f : out) link.send(f);
    }
    if (now >= next_belief || c.attitude.size() != attitudes) {
      next_belief = now + o.belief_ms * 1000ULL;
      if (c.attitude.size() > 1000) c.attitude.erase(c.attitude.begin(), c.attitude.end() - 10);
      attitudes = c.attitude.size();
      const std::string line = c.beliefs(now).to_json().dump() + "\n";
      if (std::fputs(line.c_str(), stdout) == EOF || std::fflush(stdout) != 0)
        return topkit::cli::close_stdout(kTool, 2);
    }
    std::uint64_t due = std::min({next_tick, next_belief, end});
    if (script.next_at() != UINT64_MAX) due = std::min(due, start + script.next_at());
    if (follow) due = std::min(due, next_poll);
    topconf::Received r;
    while (!g_stop && c.attitude.size() == attitudes && link.next(due, r))
      c.on_frame(r.frame, r.t_us);
  }
  if (skipped > 0)
    topkit::cli::warning(kTool, std::to_string(skipped) + " intent(s) not acted on (" + o.driver +
                                    " has no such call)");
  return topkit::cli::close_stdout(kTool, 0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "A driver-like client for topconf drive: ArduPilot's Topotek or SkyDroid mount driver as "
      "the project's test clients model it, with switches for known driver bugs. Reads the "
      "intents of TOPCONF_INTENT (or --intents) and prints its beliefs as JSON Lines."};
  topkit::cli::setup_app(app, kTool);
  Options o;
  app.add_option("--driver", o.driver, "ardupilot-topotek (SIP) or ardupilot-skydroid (C12, C13)")
      ->required();
  auto* links = app.add_option_group("link", "where the device is (one of)");
  links->add_option("--pty", o.pty, "a serial line or the driver's end of a pseudo-terminal");
  links->add_option("--udp", o.udp, "HOST:PORT of the device");
  links->add_option("--tcp", o.tcp, "HOST:PORT of the device");
  links->require_option(1);
  app.add_option("--bug", o.bugs, bug_help());
  app.add_option("--intents", o.intents, "the intents file (default: $TOPCONF_INTENT; none: idle)");
  app.add_option("--model", o.model,
                 "the device's model (default: $TOPCONF_MODEL, else the "
                 "driver's first: sip, c12)");
  app.add_option("--duration", o.duration_s, "stop after this many seconds (0: at SIGTERM)")
      ->check(CLI::Range(0.0, 86400.0));
  app.add_option("--belief-ms", o.belief_ms, "print the beliefs this often")
      ->check(CLI::Range(10u, 10000u));
  if (const int rc = topkit::cli::parse(app, argc, argv); rc >= 0) return rc;

  const bool topotek = o.driver == "ardupilot-topotek";
  if (!topotek && o.driver != "ardupilot-skydroid") {
    topkit::cli::error(
        kTool, "--driver " + o.driver + ": not one of ardupilot-topotek, ardupilot-skydroid");
    return 2;
  }
  drive::Bugs bugs;
  for (const std::string& name : o.bugs) {
    const auto b = drive::parse_bug(name);
    if (!b) {
      topkit::cli::error(kTool, "--bug " + name + ": no such bug (--help lists them)");
      return 2;
    }
    if (!(topotek ? drive::info(*b).topotek : drive::info(*b).skydroid)) {
      topkit::cli::error(kTool, "--bug " + name + ": not a bug " + o.driver + " can have");
      return 2;
    }
    bugs.set(*b);
  }
  if (o.model.empty() && std::getenv("TOPCONF_MODEL")) o.model = std::getenv("TOPCONF_MODEL");
  if (o.model.empty()) o.model = topotek ? "sip" : "c12";
  const auto model = top::model_from_string(o.model);
  if (!model) {
    topkit::cli::error(kTool, "--model " + o.model + ": not a model topsim knows");
    return 2;
  }
  if (o.intents.empty() && std::getenv("TOPCONF_INTENT")) o.intents = std::getenv("TOPCONF_INTENT");
  // --persistent (TOPCONF_CASE=persistent): the file grows while we run.
  const char* case_id = std::getenv("TOPCONF_CASE");
  const bool persistent = case_id && std::string(case_id) == "persistent";
  std::vector<drive::Intent> intents;
  if (!o.intents.empty() && !persistent) {
    std::string why;
    intents = drive::load_intents(o.intents, why);
    if (!why.empty()) {
      topkit::cli::error(kTool, why);
      return 2;
    }
  }
  drive::IntentFile follow(o.intents);
  drive::IntentFile* followed = persistent && !o.intents.empty() ? &follow : nullptr;

  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
  try {
    const std::string target = !o.pty.empty()   ? "serial:" + o.pty
                               : !o.udp.empty() ? "udp://" + o.udp
                                                : "tcp://" + o.tcp;
    // UDP: an ephemeral port (several clients on one host), not connected.
    std::unique_ptr<topconf::Transport> t = topconf::open_transport(target, *model, 0);
    if (topotek) {
      TopotekClient c;
      c.bugs = bugs, c.idle = true, c.guard = true;
      return drive_loop(c, *t, o, drive::Script(std::move(intents)), followed);
    }
    SkyDroidDriver c;
    c.bugs = bugs, c.idle = true, c.guard = true;
    return drive_loop(c, *t, o, drive::Script(std::move(intents)), followed);
  } catch (const topconf::TransportError& e) {
    if (g_stop) return topkit::cli::close_stdout(kTool, 0);
    topkit::cli::error(kTool, e.what());
    return topkit::cli::close_stdout(kTool, 1);
  }
}
