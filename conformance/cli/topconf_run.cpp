// topconf run: a matrix against a target, with the console table and the
// JSON, JUnit, HTML and pcap outputs.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "conf/report.hpp"
#include "conf/runner.hpp"
#include "conf/transport.hpp"
#include "drivers/compat.hpp"
#include "fault_arg.hpp"
#include "top/probe.hpp"
#include "topkit/model.hpp"

namespace topconf::cli {

namespace {

class RunCommand : public topkit::cli::Subcommand {
 public:
  explicit RunCommand(CLI::App& app);
  int run() override;

 private:
  TargetArgs t_;
  OutputArgs out_;
  std::string model_name_, matrix_path_, driver_, firmware_;
  std::vector<std::string> case_ids_, tags_, levels_;
  std::uint64_t seed_ = 0;
  std::uint32_t retries_ = 0, timeout_ms_ = 0, settle_ms_ = 0;
  bool no_color_ = false, quiet_ = false;
  CLI::Option *seed_opt_ = nullptr, *retries_opt_ = nullptr, *timeout_opt_ = nullptr,
              *settle_opt_ = nullptr;
};

}  // namespace

RunCommand::RunCommand(CLI::App& app)
    : Subcommand(app, "run", "run a matrix against a target (default: an in-process topsim)") {
  sub_->add_option("--target", t_.target,
                   "udp://HOST:PORT, tcp://HOST:PORT or serial:DEVICE[@BAUD]");
  sub_->add_option("--model", model_name_,
                   top::model_list("|", "|") +
                       " (with --driver: one the driver flies, default "
                       "its first)");
  sub_->add_option("--driver", driver_,
                   "check what this driver needs (topconf drivers lists them) and give its "
                   "verdict: compatible, compatible without: FEATURES, or incompatible");
  sub_->add_option("--matrix", matrix_path_,
                   "matrix JSON (default: <model>.json in share/topkit/matrices next to the "
                   "binary; topconf models --paths)");
  sub_->add_option("--case", case_ids_, "run only these case ids (globs with * and ?)");
  std::string probes;  // from the catalog (top/probe.hpp)
  for (const top::Model m : top::all_models()) {
    probes += std::string(probes.empty() ? "" : "; ") + std::string(top::to_string(m)) + ":";
    for (const top::LivenessProbe& p : top::liveness_probes(m))
      probes += " " + std::string(p.ident);
  }
  sub_->footer(
      "Liveness: before the run, the matrix's probe, or else the catalog's probes for "
      "the model (" +
      probes +
      "), are tried in order until one is answered; it is sent again after every "
      "case. \"probe unanswered: IDENT\" names those a reachable device left "
      "unanswered; a target that sends no frame at all is unreachable (exit 2).");
  sub_->add_option("--tag", tags_, "run only cases with one of these tags");
  sub_->add_option("--level", levels_, "run only cases of these levels (must, should, may)");
  seed_opt_ = sub_->add_option("--seed", seed_, "shuffle the case order with this seed");
  retries_opt_ =
      sub_->add_option("--retries", retries_, "retries of a failing case (default: the matrix's)");
  timeout_opt_ = sub_->add_option("--timeout-ms", timeout_ms_,
                                  "reply timeout per step (default: the matrix's)");
  settle_opt_ = sub_->add_option("--settle-ms", settle_ms_,
                                 "watch this long for duplicate replies (default: the matrix's)");
  sub_->add_option("--json", out_.json, "write results with timestamped transcripts as JSON");
  sub_->add_option("--junit", out_.junit, "write JUnit XML");
  sub_->add_option("--html", out_.html, "write a self-contained HTML report");
  sub_->add_option("--pcap", out_.pcap, "write every frame of the run to a pcap");
  sub_->add_option("--firmware", firmware_,
                   "the firmware under test, as NAME@VERSION: the JSON's firmware, topconf "
                   "table's column (default: the model)");
  sub_->add_option("--sim-fault", t_.sim_faults,
                   "in-process topsim only: inject these faults (as topsim --fault)");
  sub_->add_option("--sim-seed", t_.sim_seed, "in-process topsim only: fault seed");
  sub_->add_option("--bind", t_.bind_port,
                   "UDP: local port to receive on (default: 9004 for sip, ephemeral otherwise)");
  sub_->add_flag("--no-color", no_color_, "no ANSI colours in the table");
  sub_->add_flag("-q,--quiet", quiet_, "print the summary only");
}

namespace {

// The driver's profile and its matrix for the run's model; the exit status
// on failure (2).
std::optional<int> driver_matrix_of(const std::string& name, std::string& model_name,
                                    const drivers::Profile*& profile, Matrix& out) {
  profile = drivers::find_profile(name);
  if (!profile) {
    spdlog::error("--driver: unknown driver '{}' (topconf drivers lists them)", name);
    return 2;
  }
  if (model_name.empty()) model_name = std::string(top::to_string(profile->models.front()));
  const auto model = topkit::cli::model_arg(kTool, model_name);
  if (!model) return 2;
  if (!profile->serves(*model)) {
    std::string names;
    for (top::Model m : profile->models) names += " " + std::string(top::to_string(m));
    spdlog::error("--driver {} flies{}; not {}", name, names, model_name);
    return 2;
  }
  auto loaded = drivers::driver_matrix(*profile, *model);
  if (!loaded.matrix) {
    for (const std::string& e : loaded.errors) spdlog::error("{}", e);
    return 2;
  }
  out = std::move(*loaded.matrix);
  out.model = *model;
  return std::nullopt;
}

}  // namespace

int RunCommand::run() {
  std::vector<Level> lv;
  for (const auto& l : levels_) {
    const auto i = topkit::cli::one_of(kTool, "--level", l, {"must", "should", "may"});
    if (!i) return 2;
    lv.push_back(*level_from_string(l));
  }
  Matrix matrix;
  const drivers::Profile* profile = nullptr;
  if (!driver_.empty() && !matrix_path_.empty()) {
    spdlog::error("--driver makes its own matrix: no --matrix with it");
    return 2;
  }
  if (!driver_.empty()) {
    if (auto rc = driver_matrix_of(driver_, model_name_, profile, matrix)) return *rc;
  } else if (model_name_.empty()) {
    spdlog::error("--model is required (or --driver)");
    return 2;
  } else if (auto rc = load_run_matrix(model_name_, matrix_path_, matrix)) {
    return *rc;
  }
  // The in-process topsim on the driver's link: a serial line for a serial driver.
  const topsim::Link sim_link = profile && profile->link.kind == drivers::LinkKind::serial
                                    ? topsim::Link::uart
                                    : topsim::Link::network;
  if (!t_.target.empty() && !t_.sim_faults.empty()) {
    spdlog::error("--sim-fault applies to the in-process topsim only (no --target)");
    return 2;
  }
  if (!topsim::cli::fault_names_valid(kTool, "--sim-fault", t_.sim_faults)) return 2;
  std::unique_ptr<Transport> transport;
  std::unique_ptr<pcapio::Recorder> pcap;
  try {
    transport = open_target(t_.target.empty(), t_.target, matrix.model, t_.sim_faults, t_.sim_seed,
                            t_.bind_port, sim_link);
    if (!out_.pcap.empty()) pcap = std::make_unique<pcapio::Recorder>(out_.pcap, transport->tcp());
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  RunOptions opts;
  opts.cases = case_ids_;
  opts.tags = tags_;
  opts.levels = lv;
  if (seed_opt_->count()) opts.seed = seed_;
  if (retries_opt_->count()) opts.retries = retries_;
  if (timeout_opt_->count()) opts.timeout_ms = timeout_ms_;
  if (settle_opt_->count()) opts.settle_ms = settle_ms_;
  opts.pcap = pcap.get();
  const auto result = run_matrix(matrix, *transport, opts);
  if (pcap) pcap->flush();
  std::optional<drivers::Compatibility> compat;
  if (profile) compat = drivers::assess(*profile, result);
  const drivers::Compatibility* c = compat ? &*compat : nullptr;

  if (quiet_) {
    std::ostringstream all;
    write_console(all, result, false, c);
    const std::string s = all.str();
    const auto pos = s.rfind("\n\n");
    std::cout << (pos == std::string::npos ? s : s.substr(pos + 2));
  } else {
    write_console(std::cout, result, !no_color_ && ::isatty(1), c);
  }
  bool ok = true;
  if (!out_.json.empty())
    ok &= write_output(out_.json, [&](std::ostream& o) {
      nlohmann::json j = to_json(result, c);
      if (!firmware_.empty()) j["firmware"] = firmware_;
      if (!out_.pcap.empty()) j["capture"] = out_.pcap;  // topconf table links it
      o << j.dump(2) << "\n";
    });
  if (!out_.junit.empty())
    ok &= write_output(out_.junit, [&](std::ostream& o) { write_junit(o, result, c); });
  if (!out_.html.empty())
    ok &= write_output(out_.html, [&](std::ostream& o) { write_html(o, result, c); });
  if (!ok) return 2;
  return c ? c->exit_code() : result.exit_code();
}

std::unique_ptr<topkit::cli::Subcommand> run_command(CLI::App& app) {
  return std::make_unique<RunCommand>(app);
}

}  // namespace topconf::cli
