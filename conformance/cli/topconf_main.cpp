// topconf: runs a conformance matrix against a TOP device (or an in-process
// topsim) and reports per case; generates and validates matrices.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "conf/generate.hpp"
#include "conf/matrix.hpp"
#include "conf/report.hpp"
#include "conf/runner.hpp"
#include "conf/transport.hpp"
#include "topkit/cli.hpp"

#ifndef TOPKIT_MATRIX_DIR
#define TOPKIT_MATRIX_DIR "conformance/matrices"
#endif

namespace {

bool read_file(const std::string& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  out = ss.str();
  return true;
}

template <class F>
bool write_output(const std::string& path, F&& f) {
  std::ofstream out(path, std::ios::binary);
  if (!out) {
    spdlog::error("{}: cannot write", path);
    return false;
  }
  f(out);
  out.close();
  if (out.fail()) spdlog::error("{}: write error", path);
  return !out.fail();
}

std::string matrix_dir() {
  if (const char* e = std::getenv("TOPCONF_MATRIX_DIR")) return e;
  return TOPKIT_MATRIX_DIR;
}

}  // namespace

int main(int argc, char** argv) {
  // Logs go to stderr; stdout carries results (topsim: the address it serves).
  spdlog::set_default_logger(spdlog::stderr_color_mt("topconf"));
  CLI::App app{"topconf: conformance runner for the TOP gimbal-camera protocol"};
  topkit::cli::setup_app(app, "topconf");
  app.require_subcommand(1);

  // run
  auto* run =
      app.add_subcommand("run", "run a matrix against a target (default: an in-process topsim)");
  std::string target, model_name, matrix_path, json_out, junit_out, html_out, pcap_out, sim_faults;
  std::vector<std::string> case_ids, tags, levels;
  std::uint64_t seed = 0, sim_seed = 1;
  std::uint32_t retries = 0, timeout_ms = 0, settle_ms = 0;
  int bind_port = -1;
  bool no_color = false, quiet = false;
  run->add_option("--target", target, "udp://HOST:PORT, tcp://HOST:PORT or serial:DEVICE[@BAUD]");
  run->add_option("--model", model_name, top::model_list("|", "|"))->required();
  run->add_option("--matrix", matrix_path,
                  "matrix JSON (default: conformance/matrices/<model>.json)");
  run->add_option("--case", case_ids, "run only these case ids (globs with * and ?)");
  run->add_option("--tag", tags, "run only cases with one of these tags");
  run->add_option("--level", levels, "run only cases of these levels (must, should, may)");
  auto* seed_opt = run->add_option("--seed", seed, "shuffle the case order with this seed");
  auto* retries_opt =
      run->add_option("--retries", retries, "retries of a failing case (default: the matrix's)");
  auto* timeout_opt =
      run->add_option("--timeout-ms", timeout_ms, "reply timeout per step (default: the matrix's)");
  auto* settle_opt = run->add_option(
      "--settle-ms", settle_ms, "watch this long for duplicate replies (default: the matrix's)");
  run->add_option("--json", json_out, "write results with timestamped transcripts as JSON");
  run->add_option("--junit", junit_out, "write JUnit XML");
  run->add_option("--html", html_out, "write a self-contained HTML report");
  run->add_option("--pcap", pcap_out, "write every frame of the run to a pcap");
  run->add_option("--sim-fault", sim_faults,
                  "in-process topsim only: inject these faults (as topsim --fault)");
  run->add_option("--sim-seed", sim_seed, "in-process topsim only: fault seed");
  run->add_option("--bind", bind_port,
                  "UDP: local port to receive on (default: 9004 for sip, ephemeral otherwise)");
  run->add_flag("--no-color", no_color, "no ANSI colours in the table");
  run->add_flag("-q,--quiet", quiet, "print the summary only");

  // fuzz (conf/fuzz_cli.cpp): --model and --matrix are run's variables.
  topconf::FuzzCommand fuzz(app, model_name, matrix_path);

  // generate
  auto* gen =
      app.add_subcommand("generate", "write a model's default matrix generated from the catalog");
  std::string gen_model, gen_out;
  gen->add_option("--model", gen_model, top::model_list("|", "|"))->required();
  gen->add_option("-o,--output", gen_out, "output file (default: stdout)");

  // models
  auto* models = app.add_subcommand("models", "list the models, one per line (the catalog's)");

  // validate
  auto* val = app.add_subcommand("validate", "check matrix files against the schema rules");
  std::vector<std::string> val_files;
  val->add_option("files", val_files, "matrix files")->required();

  if (int rc = topkit::cli::parse_or_exit(app, argc, argv); rc >= 0) return rc;

  if (*models) {
    for (top::Model m : top::all_models()) std::cout << top::to_string(m) << "\n";
    return topkit::cli::close_stdout("topconf", 0);
  }

  if (*gen) {
    auto m = top::model_from_string(gen_model);
    if (!m || *m == top::Model::unknown) {
      spdlog::error("--model {}: not one of {}", gen_model, top::model_list());
      return 2;
    }
    const std::string text = topconf::generate_matrix(*m).dump(2) + "\n";
    if (gen_out.empty()) {
      std::cout << text;
    } else if (!write_output(gen_out, [&](std::ostream& o) { o << text; })) {
      return 2;
    }
    return 0;
  }

  if (*val) {
    int rc = 0;
    for (const auto& f : val_files) {
      std::string text;
      if (!read_file(f, text)) {
        std::cerr << f << ": cannot read\n";
        rc = 2;
        continue;
      }
      auto r = topconf::load_matrix(text, f);
      for (const auto& e : r.errors) std::cerr << e << "\n";
      if (!r.errors.empty())
        rc = std::max(rc, 1);
      else
        std::cout << f << ": ok, " << r.matrix->cases.size() << " case(s)\n";
    }
    return rc;
  }

  auto model = top::model_from_string(model_name);
  if (!model || *model == top::Model::unknown) {
    spdlog::error("--model {}: not one of {}", model_name, top::model_list());
    return 2;
  }
  std::vector<topconf::Level> lv;
  for (const auto& l : levels) {
    auto x = topconf::level_from_string(l);
    if (!x) {
      spdlog::error("--level {}: not one of must, should, may", l);
      return 2;
    }
    lv.push_back(*x);
  }
  // The matrix.
  std::string text, file = matrix_path;
  if (file.empty()) {
    file = matrix_dir() + "/" + model_name + ".json";
    if (!read_file(file, text)) {
      spdlog::warn("{}: not found; generating the default matrix from the catalog", file);
      text = topconf::generate_matrix(*model).dump();
      file = "(generated " + model_name + ")";
    }
  } else if (!read_file(file, text)) {
    spdlog::error("{}: cannot read", file);
    return 2;
  }
  auto loaded = topconf::load_matrix(text, file);
  if (!loaded.matrix) {
    for (const auto& e : loaded.errors) std::cerr << e << "\n";
    return 2;
  }
  topconf::Matrix& matrix = *loaded.matrix;
  if (matrix.model != *model)
    spdlog::warn("{} is written for {}; running it as {}", file, top::to_string(matrix.model),
                 model_name);
  matrix.model = *model;
  matrix.dialect = top::dialect_of(*model);

  if (fuzz.selected()) return fuzz.run(matrix);

  // The target.
  if (!target.empty() && !sim_faults.empty()) {
    spdlog::error("--sim-fault applies to the in-process topsim only (no --target)");
    return 2;
  }
  std::unique_ptr<topconf::Transport> transport;
  try {
    transport =
        topconf::open_target(target.empty(), target, *model, sim_faults, sim_seed, bind_port);
  } catch (const topconf::TransportError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }

  std::unique_ptr<pcapio::Recorder> pcap;
  if (!pcap_out.empty()) {
    try {
      pcap = std::make_unique<pcapio::Recorder>(pcap_out, transport->tcp());
    } catch (const std::exception& e) {
      spdlog::error("{}", e.what());
      return 2;
    }
  }
  topconf::RunOptions opts;
  opts.cases = case_ids;
  opts.tags = tags;
  opts.levels = lv;
  if (seed_opt->count()) opts.seed = seed;
  if (retries_opt->count()) opts.retries = retries;
  if (timeout_opt->count()) opts.timeout_ms = timeout_ms;
  if (settle_opt->count()) opts.settle_ms = settle_ms;
  opts.pcap = pcap.get();
  const auto result = topconf::run_matrix(matrix, *transport, opts);
  if (pcap) pcap->flush();

  const bool color = !no_color && ::isatty(1);
  if (quiet) {
    std::ostringstream all;
    topconf::write_console(all, result, false);
    std::string s = all.str();
    auto pos = s.rfind("\n\n");
    std::cout << (pos == std::string::npos ? s : s.substr(pos + 2));
  } else {
    topconf::write_console(std::cout, result, color);
  }
  bool ok = true;
  if (!json_out.empty())
    ok &= write_output(json_out,
                       [&](std::ostream& o) { o << topconf::to_json(result).dump(2) << "\n"; });
  if (!junit_out.empty())
    ok &= write_output(junit_out, [&](std::ostream& o) { topconf::write_junit(o, result); });
  if (!html_out.empty())
    ok &= write_output(html_out, [&](std::ostream& o) { topconf::write_html(o, result); });
  if (!ok) return 2;
  return topkit::cli::close_stdout("topconf", result.exit_code());
}
