// topconf table: several `topconf run --driver ... --json` reports merged
// into one compatibility table (docs/COMPAT.md, "The table"): rows are the
// driver cases grouped by grade (must, should, info), columns firmware x
// driver, cells the graded verdicts, each linking the run's capture when
// the report names one; a header row gives each column's verdict.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace topconf {

// One report read: its file name (as given) and its JSON.
struct TableInput {
  std::string file;
  nlohmann::json report;
};

// Why `report` cannot be a column (not a topconf run --driver report: no
// `compatibility` object, no cases); empty when it can.
std::string table_input_error(const nlohmann::json& report);

// The table as one JSON document ("tool": "topconf", "table": columns and
// rows; every cell names its column by index).
nlohmann::json table_json(const std::vector<TableInput>& inputs);
// The same table as a self-contained HTML page (write_html_head's style).
void write_table_html(std::ostream& os, const nlohmann::json& table);

}  // namespace topconf
