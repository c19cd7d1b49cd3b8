// topconf drive's outputs (docs/DRIVE.md): the console summary, the JSON
// report, JUnit and one HTML page; and the table of several agents' runs
// (--agent: one column per agent, one row per case ID).
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "conf/table.hpp"
#include "drive/runner.hpp"

namespace topconf {

// A line per case (unless `lines` is false: they were printed as the cases
// ended), then the summary.
void write_drive_console(std::ostream& os, const drive::DriveRun& r, bool color, bool lines = true);
// One line per case as it ends (the console's progress).
void write_drive_case_line(std::ostream& os, const drive::CaseResult& c, bool color);
nlohmann::json drive_json(const drive::DriveRun& r);
void write_drive_junit(std::ostream& os, const drive::DriveRun& r);
// `base`: where the run's --out is seen from the page (its links to the
// cases' captures and stderr), "" when the page is in it.
void write_drive_html(std::ostream& os, const drive::DriveRun& r, const std::string& base = "");

// Why `report` cannot be a column of the agents' table (not a topconf
// drive report); empty when it can.
std::string drive_table_input_error(const nlohmann::json& report);
// The agents' table as one document: columns (agent, model, link, exec,
// summary, exit_code, file) and rows (id, section, title, cells naming
// their column by index: grade, reason, folder).
nlohmann::json drive_table_json(const std::vector<TableInput>& inputs);
void write_drive_table_html(std::ostream& os, const nlohmann::json& table);

}  // namespace topconf
