// topconf drive --persistent (docs/DRIVE.md): one driver process stays
// connected to one device on one link; the device changes case in place
// (topsim::Server::reconfigure) and the intents file grows, each case's
// lines after a {"do":"case"} line.
#include <filesystem>
#include <fstream>

#include "runner_detail.hpp"
#include "session.hpp"

namespace topconf::drive::detail {

namespace fs = std::filesystem;

namespace {

// The frames of [from, to) seconds, re-stamped from `from`.
std::vector<WireFrame> slice(const std::vector<WireFrame>& all, double from, double to) {
  std::vector<WireFrame> out;
  for (const WireFrame& w : all)
    if (w.t >= from && w.t < to) {
      out.push_back(w);
      out.back().t -= from;
    }
  return out;
}

CaseResult error_result(const CaseSpec& c, std::string why) {
  CaseResult r;
  r.spec = &c;
  r.verdict = Verdict{Grade::error, std::move(why), {}};
  return r;
}

}  // namespace

void run_persistent(const DriveOptions& o, DriveRun& run) {
  if (o.cases.empty()) return;
  const fs::path dir = fs::path(o.out_dir) / "persistent";
  const std::string folder = "persistent";
  const std::string capture = folder + "/" + capture_name(o.link);
  const std::string stderr_path = folder + "/stderr.txt";
  std::vector<CaseSetup> setups;
  for (const CaseSpec* c : o.cases) setups.push_back(setup_case(*c, o.model, o.link, o.full));
  try {
    fs::create_directories(dir);
    const std::string intents = (dir / "intents.jsonl").string();
    write_intents(intents, {}, 0, false);
    DeviceRun dev(o, setups.front(), (fs::path(o.out_dir) / capture).string());
    const auto link = dev.link_values();
    auto values = link;
    values.emplace_back("case", "persistent");
    values.emplace_back("intent", intents);
    BeliefLog log;
    std::ofstream stdout_copy(dir / "stdout.txt");
    std::mutex copy_mu;
    const Steady::time_point t0 = Steady::now();
    dev.set_t0(t0);
    double total = 0;
    for (const CaseSetup& s : setups) total += s.not_applicable.empty() ? s.duration_s : 0;
    DriverProcess p(substitute(o.exec, values), dir.string(),
                    environment(o, "persistent", intents, link, total, t0),
                    (fs::path(o.out_dir) / stderr_path).string(),
                    [&](Steady::time_point at, std::string line) {
                      log.take(t0, at, line);
                      std::lock_guard lock(copy_mu);
                      stdout_copy << line << "\n";
                    });
    auto now = [&] { return std::chrono::duration<double>(Steady::now() - t0).count(); };
    std::vector<Record> records(o.cases.size());
    std::vector<double> starts(o.cases.size(), -1);
    for (std::size_t i = 0; i < o.cases.size(); ++i) {
      const CaseSetup& s = setups[i];
      if (!s.not_applicable.empty()) continue;
      Record& r = records[i];
      r.intents = s.intents;
      r.duration_s = s.duration_s;
      if (!dev.server().reconfigure(s.faults, s.options))
        throw std::runtime_error("the device did not change case");
      const double start = now();
      starts[i] = start;
      dev.identity(r);
      if (s.faults.reboot_us) r.reboot_at = static_cast<double>(s.faults.reboot_us) / 1e6;
      const nlohmann::json head = {{"t", start},
                                   {"do", "case"},
                                   {"id", std::string(o.cases[i]->id)},
                                   {"duration", s.duration_s}};
      write_intents(intents, s.intents, start, true, &head);
      for (double t = 0; t < s.duration_s; t = now() - start) {
        if (at_once(p, now())) {
          p.stop();
          const std::string why = tail_of((fs::path(o.out_dir) / stderr_path).string());
          throw std::runtime_error("the driver exited (" + p.status() + ")" +
                                   (why.empty() ? "" : ": " + why));
        }
        dev.sample(r.truth, t);
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }
    const std::string how = p.stop();
    dev.stop();
    const std::vector<WireFrame> all = dev.frames();
    std::string note;
    const std::vector<Diagnosis> diag =
        diagnose(find_topdump(o.topdump), o.model, (fs::path(o.out_dir) / capture).string(), note);
    for (std::size_t i = 0; i < o.cases.size(); ++i) {
      const CaseSpec& c = *o.cases[i];
      CaseResult res;
      res.spec = &c;
      res.folder = folder;
      res.duration_s = setups[i].duration_s;
      if (starts[i] < 0) {
        res.verdict = Verdict{Grade::informational, setups[i].not_applicable, {}};
      } else {
        Record& r = records[i];
        r.wire = slice(all, starts[i], starts[i] + r.duration_s);
        log.slice(starts[i], starts[i] + r.duration_s, r);
        res.capture = capture;
        res.stderr_path = stderr_path;
        res.driver_exit = how;
        res.started_s = starts[i];
        res.folder = folder + "/" + std::string(c.id);
        fs::create_directories(fs::path(o.out_dir) / res.folder);
        finish(o, c, setups[i], r, res);
        res.diagnoses = diag;
        res.diagnoses_note =
            note.empty() ? "persistent: the diagnoses of the whole run's capture" : note;
      }
      run.cases.push_back(std::move(res));
      if (o.on_case) o.on_case(run.cases.back());
    }
  } catch (const std::exception& e) {
    run.cases.clear();
    for (const CaseSpec* c : o.cases) run.cases.push_back(error_result(*c, e.what()));
  }
}

}  // namespace topconf::drive::detail
