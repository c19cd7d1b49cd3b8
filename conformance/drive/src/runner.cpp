// One case of topconf drive, the cases side by side (--jobs), the run.
#include "drive/runner.hpp"

#include <algorithm>
#include <atomic>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "process.hpp"
#include "runner_detail.hpp"
#include "session.hpp"

namespace topconf::drive {

using namespace detail;
namespace fs = std::filesystem;

std::string_view to_string(topsim::TransportKind k) noexcept {
  switch (k) {
    case topsim::TransportKind::udp:
      return "udp";
    case topsim::TransportKind::tcp:
      return "tcp";
    case topsim::TransportKind::pty:
      return "pty";
    case topsim::TransportKind::serial:
      return "serial";
  }
  return "?";
}

int DriveRun::exit_code() const {
  if (!error.empty()) return 2;
  std::vector<Grade> g;
  for (const CaseResult& c : cases) g.push_back(c.verdict.grade);
  return exit_code_of(g);
}

std::size_t DriveRun::count(Grade g) const {
  return static_cast<std::size_t>(std::count_if(
      cases.begin(), cases.end(), [g](const CaseResult& c) { return c.verdict.grade == g; }));
}

namespace detail {

std::vector<std::pair<std::string, std::string>> environment(
    const DriveOptions& o, const std::string& case_id, const std::string& intents,
    const std::vector<std::pair<std::string, std::string>>& link, double duration,
    Steady::time_point t0) {
  std::vector<std::pair<std::string, std::string>> env = {
      {"TOPCONF_CASE", case_id},
      {"TOPCONF_INTENT", intents},
      {"TOPCONF_MODEL", std::string(top::to_string(o.model))},
      {"TOPCONF_LINK", std::string(to_string(o.link))},
      {"TOPCONF_DURATION", std::to_string(duration)},
      // steady_clock is CLOCK_MONOTONIC (libstdc++ on Linux).
      {"TOPCONF_T0_US",
       std::to_string(
           std::chrono::duration_cast<std::chrono::microseconds>(t0.time_since_epoch()).count())}};
  for (const auto& [k, v] : link) {
    std::string up = k;
    for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    env.emplace_back("TOPCONF_" + up, v);
  }
  return env;
}

bool at_once(DriverProcess& p, double t) {
  if (!p.exited()) return false;
  return t < 0.2 || p.exit_code() == 126 || p.exit_code() == 127;
}

std::string tail_of(const std::string& path) {
  std::ifstream f(path);
  std::string s((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (s.size() > 300) s = "..." + s.substr(s.size() - 300);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

void finish(const DriveOptions& o, const CaseSpec& c, const CaseSetup& setup, Record& r,
            CaseResult& res) {
  res.verdict = grade_case(c, setup, o.model, o.link, r);
  res.beliefs = r.beliefs.size();
  res.non_json_lines = r.non_json_lines;
  res.errors = r.errors;
  // The case's truth, for a reader of the folder.
  std::ofstream t(fs::path(o.out_dir) / res.folder / "truth.csv");
  t << "t,yaw,pitch,roll,yaw_rate,pitch_rate,roll_rate,streams_on\n";
  for (const Truth& x : r.truth)
    t << x.t << "," << x.angle[0] << "," << x.angle[1] << "," << x.angle[2] << "," << x.rate[0]
      << "," << x.rate[1] << "," << x.rate[2] << "," << x.streams_on << "\n";
}

}  // namespace detail

namespace {

CaseResult run_one(const DriveOptions& o, const CaseSpec& c) {
  CaseResult res;
  res.spec = &c;
  res.folder = "cases/" + std::string(c.id);
  const fs::path dir = fs::path(o.out_dir) / res.folder;
  const CaseSetup setup = setup_case(c, o.model, o.link, o.full);
  res.duration_s = setup.duration_s;
  if (!setup.not_applicable.empty()) {
    res.verdict = Verdict{Grade::informational, setup.not_applicable, {}};
    return res;
  }
  Record r;
  r.intents = setup.intents;
  r.duration_s = setup.duration_s;
  try {
    fs::create_directories(dir);
    const std::string intents = (dir / "intents.jsonl").string();
    write_intents(intents, setup.intents, 0, false);
    res.capture = res.folder + "/" + capture_name(o.link);
    res.stderr_path = res.folder + "/stderr.txt";
    DeviceRun dev(o, setup, (fs::path(o.out_dir) / res.capture).string());
    dev.identity(r);
    const auto link = dev.link_values();
    auto values = link;
    values.emplace_back("case", std::string(c.id));
    values.emplace_back("intent", intents);
    BeliefLog log;
    std::ofstream stdout_copy(dir / "stdout.txt");
    std::mutex copy_mu;
    Steady::time_point t0 = Steady::now();
    dev.set_t0(t0);
    const std::uint64_t server_at_t0 = dev.server().now_us();
    DriverProcess p(substitute(o.exec, values), dir.string(),
                    environment(o, std::string(c.id), intents, link, setup.duration_s, t0),
                    (fs::path(o.out_dir) / res.stderr_path).string(),
                    [&](Steady::time_point at, std::string line) {
                      log.take(t0, at, line);
                      std::lock_guard lock(copy_mu);
                      stdout_copy << line << "\n";
                    });
    if (setup.faults.reboot_us)
      r.reboot_at =
          (static_cast<double>(setup.faults.reboot_us) - static_cast<double>(server_at_t0)) / 1e6;
    // The case's time: truth every 50 ms.
    for (;;) {
      const double t = std::chrono::duration<double>(Steady::now() - t0).count();
      if (t >= setup.duration_s) break;
      if (at_once(p, t)) {
        p.stop();
        res.driver_exit = p.status();
        const std::string why = tail_of((fs::path(o.out_dir) / res.stderr_path).string());
        res.verdict = Verdict{
            Grade::error,
            "the driver exited at once (" + p.status() + ")" + (why.empty() ? "" : ": " + why),
            {}};
        return res;
      }
      dev.sample(r.truth, t);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (p.exited()) res.driver_exit = p.status() + " before the end";
    const std::string how = p.stop();
    if (res.driver_exit.empty()) res.driver_exit = how;
    dev.stop();
    r.wire = dev.frames();
    log.slice(0, 1e9, r);
  } catch (const std::exception& e) {
    res.verdict = Verdict{Grade::error, e.what(), {}};
    return res;
  }
  finish(o, c, setup, r, res);
  res.diagnoses = diagnose(find_topdump(o.topdump), o.model,
                           (fs::path(o.out_dir) / res.capture).string(), res.diagnoses_note);
  return res;
}

std::string iso_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return b;
}

}  // namespace

DriveRun run_drive(const DriveOptions& given) {
  DriveRun run;
  run.options = given;
  // The driver runs in its case's folder: every path it is given is absolute.
  DriveOptions o = given;
  std::error_code aec;
  o.out_dir = fs::absolute(given.out_dir, aec).lexically_normal().string();
  run.options.out_dir = o.out_dir;
  run.started = iso_now();
  const auto t0 = Steady::now();
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (ec) {
    run.error = o.out_dir + ": " + ec.message();
    return run;
  }
  if (o.persistent) {
    run_persistent(o, run);
  } else {
    run.cases.resize(o.cases.size());
    std::atomic<std::size_t> next{0};
    std::mutex mu;
    auto worker = [&] {
      for (std::size_t i; (i = next++) < o.cases.size();) {
        run.cases[i] = run_one(o, *o.cases[i]);
        if (o.on_case) {
          std::lock_guard lock(mu);
          o.on_case(run.cases[i]);
        }
      }
    };
    std::vector<std::thread> pool;
    const unsigned n =
        std::max(1u, std::min<unsigned>(o.jobs, static_cast<unsigned>(o.cases.size())));
    for (unsigned i = 0; i < n; ++i) pool.emplace_back(worker);
    for (auto& th : pool) th.join();
  }
  run.seconds = std::chrono::duration<double>(Steady::now() - t0).count();
  for (const CaseResult& c : run.cases)
    if (c.verdict.grade == Grade::error && run.error.empty())
      run.error = "case " + std::string(c.spec->id) + ": " + c.verdict.reason;
  return run;
}

}  // namespace topconf::drive
