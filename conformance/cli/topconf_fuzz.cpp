// topconf fuzz: generated and mutated frames against a device, with
// liveness probes, minimisation and the JSON Lines, JUnit, HTML and pcap
// outputs.
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "conf/fuzz.hpp"
#include "conf/fuzz_report.hpp"
#include "conf/runner.hpp"
#include "conf/transport.hpp"
#include "fault_arg.hpp"

namespace topconf::cli {

namespace {

class FuzzCommand : public topkit::cli::Subcommand {
 public:
  explicit FuzzCommand(CLI::App& app);
  int run() override;

 private:
  int run(const Matrix& matrix);
  std::optional<int> resume(top::Model model, FuzzOptions& o, bool& append);
  TargetArgs t_;
  OutputArgs out_;
  std::string model_name_, matrix_path_, resume_, restart_cmd_;
  std::uint64_t seed_ = 1, cases_ = 0, start_ = 0, end_ = 0;
  std::vector<std::uint64_t> only_;
  double duration_ = 0, rate_ = 0;
  std::uint32_t probe_every_ = 1, timeout_ms_ = 300, slow_ms_ = 1000, recover_ms_ = 3000;
  std::size_t window_ = 8, max_failures_ = 0;
  std::uint32_t probe_timeout_ms_ = 0;
  bool no_minimise_ = false, quiet_ = false;
  CLI::Option *seed_opt_ = nullptr, *cases_opt_ = nullptr, *start_opt_ = nullptr,
              *end_opt_ = nullptr;
};

}  // namespace

FuzzCommand::FuzzCommand(CLI::App& app)
    : Subcommand(app, "fuzz",
                 "send generated and mutated frames to a device, probe that it still answers "
                 "after each case, minimise what breaks it (docs/TOPCONF-FUZZ.md)") {
  sub_->add_option("--model", model_name_, top::model_list("|", "|"))->required();
  sub_->add_option("--target", t_.target,
                   "udp://HOST:PORT, tcp://HOST:PORT, serial:DEVICE[@BAUD] or sim (an "
                   "in-process topsim)")
      ->required();
  sub_->add_option("--matrix", matrix_path_,
                   "matrix JSON for the levels and a probe of its own (without one, the catalog's "
                   "probes for the model; default: <model>.json in share/topkit/matrices next "
                   "to the binary; topconf models --paths)");
  seed_opt_ = sub_->add_option("--seed", seed_, "seed of the mutations")->capture_default_str();
  cases_opt_ = sub_->add_option("--cases", cases_, "run this many cases (default 10000)");
  start_opt_ = sub_->add_option("--start", start_, "first case index (default 0)");
  end_opt_ = sub_->add_option("--end", end_, "stop before this case index");
  sub_->add_option("--case", only_, "run only these case indices");
  sub_->add_option("--duration", duration_, "stop after this many seconds");
  sub_->add_option("--rate", rate_, "at most this many cases per second");
  sub_->add_option("--resume", resume_,
                   "continue the session of this --json file after its last case (appends "
                   "to it unless --json names another file)");
  sub_->add_option("--probe-every", probe_every_, "liveness probe every N cases")
      ->capture_default_str();
  sub_->add_option("--timeout-ms", timeout_ms_, "wait this long for a promised answer")
      ->capture_default_str();
  sub_->add_option("--slow-ms", slow_ms_, "an answer later than this after a case is a failure")
      ->capture_default_str();
  sub_->add_option("--recover-ms", recover_ms_,
                   "after the device stopped (and --restart-cmd), wait this long for it to "
                   "answer again")
      ->capture_default_str();
  sub_->add_option("--restart-cmd", restart_cmd_,
                   "shell command that restarts the device (topsim: kill -HUP PID)");
  sub_->add_option("--window", window_, "cases kept before a failure, replayed to minimise it")
      ->capture_default_str();
  sub_->add_option("--max-failures", max_failures_, "stop after this many failures (0: never)")
      ->capture_default_str();
  sub_->add_option("--probe-timeout-ms", probe_timeout_ms_,
                   "wait this long for the probe's answer (default: the matrix's)");
  sub_->add_flag("--no-minimise", no_minimise_, "report failures without replaying them");
  sub_->add_option("--json", out_.json, "write JSON Lines: every case with its bytes and verdict");
  sub_->add_option("--junit", out_.junit, "write JUnit XML, one testcase per failure class");
  sub_->add_option("--html", out_.html, "write a self-contained HTML report");
  sub_->add_option("--pcap", out_.pcap, "write every case sent and every answer to a pcap");
  sub_->add_option("--sim-fault", t_.sim_faults, "--target sim: faults (as topsim --fault)");
  sub_->add_option("--sim-seed", t_.sim_seed, "--target sim: fault seed");
  sub_->add_option("--bind", t_.bind_port, "UDP: local port to receive on (default: 9004 for sip)");
  sub_->add_flag("-q,--quiet", quiet_, "no progress lines");
}

// --resume: the seed and the next index from the file's session; `append`
// when the --json file is the one resumed.
std::optional<int> FuzzCommand::resume(top::Model model, FuzzOptions& o, bool& append) {
  std::ifstream in(resume_);
  if (!in) {
    spdlog::error("--resume {}: cannot read", resume_);
    return 2;
  }
  std::string line;
  std::size_t n = 0;
  bool have_session = false;
  std::optional<std::uint64_t> last;
  while (std::getline(in, line)) {
    ++n;
    const auto j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      spdlog::error("--resume {}: line {}: not JSON", resume_, n);
      return 2;
    }
    if (j.contains("session")) {
      have_session = true;
      if (j.value("model", "") != top::to_string(model)) {
        spdlog::error("--resume {}: line {}: the session is for model {}", resume_, n,
                      j.value("model", "?"));
        return 2;
      }
      if (!seed_opt_->count()) o.seed = j.value("seed", std::uint64_t{1});
    } else if (j.contains("index") && j["index"].is_number_unsigned()) {
      last = std::max(last.value_or(0), j["index"].get<std::uint64_t>());
    }
  }
  if (!have_session) {
    spdlog::error("--resume {}: no session line (not a topconf fuzz --json file)", resume_);
    return 2;
  }
  if (!start_opt_->count()) o.start = last ? *last + 1 : 0;
  if (out_.json.empty() || out_.json == resume_) {
    out_.json = resume_;
    append = true;
  }
  spdlog::info("resuming {} at case {} (seed {})", resume_, o.start, o.seed);
  return std::nullopt;
}

int FuzzCommand::run() {
  Matrix matrix;
  if (auto rc = load_run_matrix(model_name_, matrix_path_, matrix)) return *rc;
  return run(matrix);
}

int FuzzCommand::run(const Matrix& loaded) {
  Matrix matrix = loaded;
  if (probe_timeout_ms_) matrix.probe_timeout_ms = probe_timeout_ms_;
  const top::Model model = matrix.model;
  FuzzOptions o;
  o.seed = seed_;
  o.start = start_;
  o.only = only_;
  o.duration_s = duration_;
  o.rate = rate_;
  o.probe_every = std::max<std::uint32_t>(1, probe_every_);
  o.timeout_ms = timeout_ms_;
  o.slow_ms = slow_ms_;
  o.recover_ms = recover_ms_;
  o.window = window_;
  o.minimise = !no_minimise_;
  o.max_failures = max_failures_;

  // --resume: the seed and the next index from the file's session.
  bool append = false;
  if (!resume_.empty()) {
    if (auto rc = resume(model, o, append)) return *rc;
  }
  if (end_opt_->count()) o.end = end_;
  if (cases_opt_->count()) o.end = o.start + cases_;
  if (!o.end && o.only.empty() && duration_ <= 0) o.end = o.start + 10000;

  const bool sim = t_.target == "sim";
  if (!sim && !t_.sim_faults.empty()) {
    spdlog::error("--sim-fault applies to --target sim only");
    return 2;
  }
  if (!topsim::cli::fault_names_valid(kTool, "--sim-fault", t_.sim_faults)) return 2;
  std::unique_ptr<Transport> transport;
  try {
    transport = open_target(sim, t_.target, model, t_.sim_faults, t_.sim_seed, t_.bind_port);
  } catch (const TransportError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  Transport& t = *transport;
  if (!restart_cmd_.empty()) {
    o.restart = [this] {
      spdlog::info("restarting the device: {}", restart_cmd_);
      const int rc = std::system(restart_cmd_.c_str());
      if (rc != 0) spdlog::warn("--restart-cmd exited with status {}", rc);
      return rc == 0;
    };
  } else if (t_.target == "sim") {
    o.restart = [&t] { return t.restart(); };
  }

  std::unique_ptr<pcapio::Recorder> pcap;
  if (!out_.pcap.empty()) {
    try {
      pcap = std::make_unique<pcapio::Recorder>(out_.pcap, t.tcp());
    } catch (const std::exception& e) {
      spdlog::error("{}", e.what());
      return 2;
    }
    o.pcap = pcap.get();
  }
  std::ofstream jl;
  if (!out_.json.empty()) {
    jl.open(out_.json, append ? std::ios::app : std::ios::trunc);
    if (!jl) {
      spdlog::error("{}: cannot write", out_.json);
      return 2;
    }
    if (!append) {
      FuzzResult head;
      head.model = model;
      head.seed = o.seed;
      head.target = t.describe();
      head.catalog_cases = CaseSource(model, t.client_address(), o.seed, &matrix).catalog_cases();
      head.started_at = iso_now();
      jl << session_json(head).dump() << "\n";
    }
    o.on_case = [&jl](const FuzzCaseResult& r) { jl << to_json(r).dump() << "\n"; };
  }
  o.on_failure = [&](const FuzzFailure& f) {
    std::cout << "FAIL " << failure_line(f) << std::endl;
    if (jl.is_open()) jl << to_json(f).dump() << "\n";
  };
  if (!quiet_)
    o.on_progress = [](std::uint64_t n, double rate, std::size_t failures) {
      std::cerr << n << " cases, " << static_cast<long>(rate) << " cases/s, " << failures
                << " failure(s)\n";
    };

  const FuzzResult res = run_fuzz(matrix, t, o);
  bool ok = true;
  if (pcap) {
    pcap->flush();
  }
  write_console(std::cout, res);
  if (jl.is_open()) {
    jl << summary_json(res).dump() << "\n";
    jl.flush();
    if (!jl) {
      spdlog::error("{}: write failed", out_.json);
      ok = false;
    }
  }
  auto write = [&](const std::string& path, auto&& f) {
    if (path.empty()) return;
    std::ofstream out(path, std::ios::binary);
    if (out) f(out);
    if (!out) {
      spdlog::error("{}: cannot write", path);
      ok = false;
    }
  };
  write(out_.junit, [&](std::ostream& os) { write_junit(os, res); });
  write(out_.html, [&](std::ostream& os) { write_html(os, res); });
  if (!ok) return 2;
  return res.exit_code();
}

std::unique_ptr<topkit::cli::Subcommand> fuzz_command(CLI::App& app) {
  return std::make_unique<FuzzCommand>(app);
}

}  // namespace topconf::cli
