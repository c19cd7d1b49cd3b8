// topconf table: `topconf run --driver ... --json` reports merged into one
// compatibility table, HTML and JSON (docs/COMPAT.md, "The table").
#include <spdlog/spdlog.h>

#include <iostream>

#include "commands.hpp"
#include "conf/table.hpp"

namespace topconf::cli {

namespace {

struct Table {
  std::vector<std::string> files;
  std::string html, json;
  void declare(CLI::App& sub) {
    sub.add_option("reports", files, "topconf run --driver --json reports")->required();
    sub.add_option("--html", html, "write the table as an HTML page (default: to stdout)");
    sub.add_option("--json", json, "write the table as one JSON document");
  }
  int run() const;
};

int Table::run() const {
  std::vector<TableInput> inputs;
  for (const std::string& f : files) {
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
  if (!json.empty()) ok &= write_output(json, [&](std::ostream& o) { o << t.dump(2) << "\n"; });
  if (!html.empty())
    ok &= write_output(html, [&](std::ostream& o) { write_table_html(o, t); });
  else if (json.empty())
    write_table_html(std::cout, t);
  return ok ? 0 : 2;
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> table_command(CLI::App& app) {
  return topkit::cli::make_subcommand<Table>(
      app, "table",
      "merge topconf run --driver --json reports into one compatibility table: rows the driver's "
      "cases by grade, columns firmware x driver (docs/COMPAT.md)");
}

}  // namespace topconf::cli
