// topconf table: `topconf run --driver ... --json` reports merged into one
// compatibility table, HTML and JSON (docs/COMPAT.md, "The table").
#include <spdlog/spdlog.h>

#include <iostream>

#include "commands.hpp"
#include "conf/table.hpp"

namespace topconf::cli {

namespace {

class TableCommand : public topkit::cli::Subcommand {
 public:
  explicit TableCommand(CLI::App& app);
  int run() override;

 private:
  std::vector<std::string> files_;
  std::string html_, json_;
};

}  // namespace

TableCommand::TableCommand(CLI::App& app)
    : Subcommand(app, "table",
                 "merge topconf run --driver --json reports into one compatibility table: rows "
                 "the driver's cases by grade, columns firmware x driver (docs/COMPAT.md)") {
  sub_->add_option("reports", files_, "topconf run --driver --json reports")->required();
  sub_->add_option("--html", html_, "write the table as an HTML page (default: to stdout)");
  sub_->add_option("--json", json_, "write the table as one JSON document");
}

int TableCommand::run() {
  std::vector<TableInput> inputs;
  for (const std::string& f : files_) {
    const auto text = read_file(f);
    if (!text) {
      spdlog::error("{}: cannot read", f);
      return 2;
    }
    auto j = nlohmann::json::parse(*text, nullptr, false);
    const std::string why = j.is_discarded() ? "not JSON" : table_input_error(j);
    if (!why.empty()) {
      spdlog::error("{}: {}", f, why);
      return 2;
    }
    inputs.push_back({f, std::move(j)});
  }
  const nlohmann::json t = table_json(inputs);
  bool ok = true;
  if (!json_.empty()) ok &= write_output(json_, [&](std::ostream& o) { o << t.dump(2) << "\n"; });
  if (!html_.empty())
    ok &= write_output(html_, [&](std::ostream& o) { write_table_html(o, t); });
  else if (json_.empty())
    write_table_html(std::cout, t);
  return ok ? 0 : 2;
}

std::unique_ptr<topkit::cli::Subcommand> table_command(CLI::App& app) {
  return std::make_unique<TableCommand>(app);
}

}  // namespace topconf::cli
