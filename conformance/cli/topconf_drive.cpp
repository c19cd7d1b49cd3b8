// topconf drive: a gimbal driver under test against a topsim device per
// case (docs/DRIVE.md): the console summary, the JSON report, JUnit, one
// HTML page, and with --agent the table of every agent run into --out.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <mutex>

#include "commands.hpp"
#include "conf/drive_report.hpp"
#include "drive/runner.hpp"
#include "topkit/model.hpp"

namespace topconf::cli {

namespace {

namespace fs = std::filesystem;

struct Drive {
  std::string model_name_, link_, exec_, out_ = "drive-out", agent_, topdump_;
  std::vector<std::string> cases_;
  bool full_ = false, persistent_ = false, no_color_ = false, quiet_ = false;
  unsigned jobs_ = 8;
  std::uint64_t seed_ = 1;
  OutputArgs files_;

  void declare(CLI::App& sub) {
    sub.add_option("--model", model_name_, top::model_list("|", "|"))->required();
    sub.add_option("--link", link_, "pty|udp|tcp (default: pty for sip, udp otherwise)")
        ->check(CLI::IsMember({"pty", "udp", "tcp"}));
    sub.add_option("--exec", exec_,
                   "the driver: run by /bin/sh -c with {pty}, {host}, {port}, {case}, {intent} "
                   "substituted; TOPCONF_CASE, TOPCONF_INTENT, TOPCONF_MODEL, TOPCONF_LINK in "
                   "its environment")
        ->required();
    sub.add_option("--case", cases_, "case IDs (2.1) or sections (2); default all");
    sub.add_flag("--full", full_, "the full durations (default: the short ones)");
    sub.add_option("--jobs", jobs_, "cases run at once (default 8)")->check(CLI::Range(1, 64));
    sub.add_flag("--persistent", persistent_,
                 "one driver process for every case: the device changes case in place");
    sub.add_option("--agent", agent_,
                   "name this run in OUT/table.html (its files go to OUT/agents/NAME/)")
        ->check([](const std::string& s) {
          for (char c : s)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
              return std::string("letters, digits, '-', '_' and '.' only");
          return s.empty() || s[0] == '.' ? std::string("must not be empty or start with '.'")
                                          : std::string();
        });
    sub.add_option("--out", out_, "the cases' folders (default drive-out)");
    sub.add_option("--json", files_.json, "write the JSON report");
    sub.add_option("--junit", files_.junit, "write JUnit XML");
    sub.add_option("--html", files_.html, "write the HTML report");
    sub.add_option("--seed", seed_, "seed of the device's faults (default 1)");
    sub.add_option("--topdump", topdump_, "topdump for the diagnoses (default: next to topconf)");
    sub.add_flag("--no-color", no_color_, "no ANSI colours");
    sub.add_flag("-q,--quiet", quiet_, "print the summary only");
  }
  int run() const;
  // Rewrites OUT/table.html and OUT/table.json from OUT/agents/*.json.
  bool write_agents_table() const;
};

}  // namespace

bool Drive::write_agents_table() const {
  std::vector<TableInput> inputs;
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(out_) / "agents", ec))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    const auto text = read_file(f.string());
    auto j = text ? nlohmann::json::parse(*text, nullptr, false) : nlohmann::json();
    const std::string why = !text              ? "cannot read"
                            : j.is_discarded() ? "not JSON"
                                               : drive_table_input_error(j);
    if (!why.empty()) {
      spdlog::warn("{}: {}: left out of the table", f.string(), why);
      continue;
    }
    inputs.push_back({f.filename().string(), std::move(j)});
  }
  const nlohmann::json t = drive_table_json(inputs);
  bool ok = write_output((fs::path(out_) / "table.json").string(),
                         [&](std::ostream& o) { o << t.dump(2) << "\n"; });
  ok &= write_output((fs::path(out_) / "table.html").string(),
                     [&](std::ostream& o) { write_drive_table_html(o, t); });
  return ok;
}

int Drive::run() const {
  drive::DriveOptions o;
  const auto model = topkit::cli::model_arg(kTool, model_name_);
  if (!model) return 2;
  o.model = *model;
  const std::string link = !link_.empty()                                      ? link_
                           : top::dialect_of(o.model) == top::Dialect::topotek ? "pty"
                                                                               : "udp";
  o.link = link == "pty"   ? topsim::TransportKind::pty
           : link == "tcp" ? topsim::TransportKind::tcp
                           : topsim::TransportKind::udp;
  std::string error;
  o.cases = drive::select_cases(cases_, error);
  if (!error.empty()) {
    spdlog::error("--case: {}", error);
    return 2;
  }
  o.exec = exec_;
  o.full = full_;
  o.jobs = jobs_;
  o.persistent = persistent_;
  o.agent = agent_;
  o.out_dir = agent_.empty() ? out_ : (fs::path(out_) / "agents" / agent_).string();
  o.seed = seed_;
  o.topdump = topdump_;
  const bool color = !no_color_ && ::isatty(1);
  std::mutex mu;
  if (!quiet_)
    o.on_case = [&](const drive::CaseResult& c) {
      std::lock_guard lock(mu);
      write_drive_case_line(std::cout, c, color);
      std::cout.flush();
    };
  const drive::DriveRun r = drive::run_drive(o);
  // The summary (the case lines came as the cases ended).
  if (!quiet_) std::cout << "\n";
  write_drive_console(std::cout, r, color, false);
  nlohmann::json j = drive_json(r);
  j["version"] = TOPKIT_VERSION;
  bool ok = true;
  if (!files_.json.empty())
    ok &= write_output(files_.json, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
  if (!files_.junit.empty())
    ok &= write_output(files_.junit, [&](std::ostream& out) { write_drive_junit(out, r); });
  if (!files_.html.empty())
    ok &= write_output(files_.html, [&](std::ostream& out) {
      // The page's links to the cases' files, from where the page is.
      std::error_code ec;
      const fs::path page_dir = fs::absolute(files_.html, ec).parent_path();
      const fs::path rel = fs::relative(fs::absolute(o.out_dir, ec), page_dir, ec);
      write_drive_html(out, r, ec ? fs::absolute(o.out_dir).string() : rel.string());
    });
  if (!agent_.empty()) {
    ok &= write_output((fs::path(out_) / "agents" / (agent_ + ".json")).string(),
                       [&](std::ostream& out) { out << j.dump(2) << "\n"; });
    ok &= write_agents_table();
  }
  if (!ok) return 2;
  return r.exit_code();
}

std::unique_ptr<topkit::cli::Subcommand> drive_command(CLI::App& app) {
  return topkit::cli::make_subcommand<Drive>(
      app, "drive",
      "put a gimbal driver (--exec) in front of every known field problem of a simulated device "
      "and grade its reaction (docs/DRIVE.md)");
}

}  // namespace topconf::cli
