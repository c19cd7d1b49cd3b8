#include "conf/drive_report.hpp"

#include <iomanip>
#include <iterator>
#include <map>

#include "conf/report.hpp"
#include "junit.hpp"
#include "top/detail/text.hpp"
#include "top/enum_names.hpp"

namespace topconf {

using DCase = drive::CaseResult;
using drive::DriveRun;
using drive::Grade;
using top::markup_escape;

namespace {

constexpr Grade kDriveGrades[] = {Grade::pass,          Grade::non_strict, Grade::informational,
                                  Grade::unimplemented, Grade::fail,       Grade::error};

// The console colour of each grade, in Grade's order: green, yellow, dim,
// dim, red, red.
constexpr std::string_view kDriveColor[] = {"\x1b[32m", "\x1b[33m", "\x1b[2m",
                                            "\x1b[2m",  "\x1b[31m", "\x1b[31m"};
static_assert(std::size(kDriveColor) == static_cast<std::size_t>(Grade::error) + 1);

std::string_view color_of(Grade g) { return top::enum_name(kDriveColor, g, "\x1b[2m"); }

// The HTML class of a grade (write_html_head's classes).
std::string html_class(std::string_view grade) {
  if (grade == "pass" || grade == "non-strict" || grade == "fail" || grade == "error")
    return std::string(grade);
  if (grade == "unimplemented") return "inconclusive";
  return "na";
}

}  // namespace

void write_drive_case_line(std::ostream& os, const DCase& c, bool color) {
  os << std::left << std::setw(5) << c.spec->id << " ";
  if (color) os << color_of(c.verdict.grade);
  os << std::setw(14) << drive::to_string(c.verdict.grade);
  if (color) os << "\x1b[0m";
  os << std::setw(36) << c.spec->title << " " << c.verdict.reason << "\n";
}

void write_drive_console(std::ostream& os, const DriveRun& r, bool color, bool lines) {
  if (!r.error.empty() && r.cases.empty()) {
    os << "topconf: drive: " << r.error << "\n";
    return;
  }
  if (lines) {
    for (const DCase& c : r.cases) write_drive_case_line(os, c, color);
    os << "\n";
  }
  os << r.cases.size() << " case(s), " << top::to_string(r.options.model) << " over "
     << drive::to_string(r.options.link) << (r.options.persistent ? " (persistent)" : "") << ", "
     << std::fixed << std::setprecision(1) << r.seconds << " s:";
  for (Grade g : kDriveGrades) os << " " << r.count(g) << " " << drive::to_string(g) << ",";
  os << " exit " << r.exit_code() << "\n";
  if (!r.error.empty()) os << "topconf: drive: " << r.error << "\n";
}

nlohmann::json drive_json(const DriveRun& r) {
  nlohmann::json j;
  j["tool"] = "topconf drive";
  j["agent"] = r.options.agent;
  j["model"] = top::to_string(r.options.model);
  j["link"] = drive::to_string(r.options.link);
  j["exec"] = r.options.exec;
  j["persistent"] = r.options.persistent;
  j["full"] = r.options.full;
  j["started"] = r.started;
  j["out"] = r.options.out_dir;  // the cases' folder, capture and stderr are relative to it
  j["seconds"] = r.seconds;
  nlohmann::json sum = nlohmann::json::object();
  for (Grade g : kDriveGrades) sum[std::string(drive::to_string(g))] = r.count(g);
  j["summary"] = sum;
  j["exit_code"] = r.exit_code();
  if (!r.error.empty()) j["error"] = r.error;
  j["cases"] = nlohmann::json::array();
  for (const DCase& c : r.cases) {
    nlohmann::json k = {{"id", c.spec->id},
                        {"title", c.spec->title},
                        {"section", c.spec->section},
                        {"good", c.spec->good},
                        {"source", c.spec->source},
                        {"needs", c.spec->needs},
                        {"grade", drive::to_string(c.verdict.grade)},
                        {"reason", c.verdict.reason},
                        {"duration_s", c.duration_s},
                        {"folder", c.folder},
                        {"capture", c.capture},
                        {"stderr", c.stderr_path},
                        {"driver_exit", c.driver_exit},
                        {"beliefs", c.beliefs},
                        {"non_json_lines", c.non_json_lines},
                        {"errors", c.errors}};
    if (r.options.persistent) k["started_s"] = c.started_s;
    k["checks"] = nlohmann::json::array();
    for (const drive::Check& ch : c.verdict.checks)
      k["checks"].push_back({{"name", ch.name}, {"ok", ch.ok}, {"detail", ch.detail}});
    k["diagnoses"] = nlohmann::json::array();
    for (const drive::Diagnosis& d : c.diagnoses)
      k["diagnoses"].push_back({{"name", d.code}, {"severity", d.severity}, {"text", d.message}});
    if (!c.diagnoses_note.empty()) k["diagnoses_note"] = c.diagnoses_note;
    j["cases"].push_back(std::move(k));
  }
  return j;
}

void write_drive_junit(std::ostream& os, const DriveRun& r) {
  detail::JunitSuite s;
  s.name = "topconf.drive." + std::string(top::to_string(r.options.model)) +
           (r.options.agent.empty() ? "" : "." + r.options.agent);
  s.tests = r.cases.size();
  s.failures = r.count(Grade::fail);
  s.errors = r.count(Grade::error);
  s.skipped = r.count(Grade::informational) + r.count(Grade::unimplemented);
  s.seconds = r.seconds;
  s.timestamp = r.started;
  detail::open_junit(os, s);
  using Result = detail::JunitCase::Result;
  for (const DCase& c : r.cases) {
    detail::JunitCase k{.classname = s.name,
                        .name = std::string(c.spec->id) + " " + std::string(c.spec->title),
                        .seconds = c.duration_s};
    const std::string graded =
        std::string(drive::to_string(c.verdict.grade)) + ": " + c.verdict.reason;
    switch (c.verdict.grade) {
      case Grade::fail:
        k.result = Result::failure;
        k.message = c.verdict.reason;
        break;
      case Grade::error:
        k.result = Result::error;
        k.message = c.verdict.reason;
        break;
      case Grade::informational:
      case Grade::unimplemented:
        k.result = Result::skipped;
        k.message = graded;
        break;
      default:
        k.out = graded;
    }
    detail::write_case(os, k);
  }
  detail::close_junit(os);
}

void write_drive_html(std::ostream& os, const DriveRun& r, const std::string& base) {
  const std::string to = base.empty() || base == "." ? "" : base + "/";
  const std::string model(top::to_string(r.options.model));
  write_html_head(os, "topconf drive " + model);
  os << "<h1>topconf drive: " << markup_escape(model) << " over "
     << drive::to_string(r.options.link) << "</h1>\n<p>Driver <code>"
     << markup_escape(r.options.exec) << "</code>"
     << (r.options.agent.empty() ? "" : ", agent <b>" + markup_escape(r.options.agent) + "</b>")
     << ", started " << markup_escape(r.started) << ", " << r.seconds << " s"
     << (r.options.persistent ? ", persistent" : "") << (r.options.full ? ", full durations" : "")
     << ".</p>\n<p class=\"sum\">";
  for (Grade g : kDriveGrades) {
    const std::string name(drive::to_string(g));
    os << "<span class=\"" << html_class(name) << "\">" << name << ": " << r.count(g) << "</span>";
  }
  os << "</p>\n<p><b>exit status " << r.exit_code() << "</b></p>\n";
  os << "<table><tr><th>case</th><th>grade</th><th>what a good driver does</th><th>reason, "
        "checks, diagnoses</th><th>files</th></tr>\n";
  for (const DCase& c : r.cases) {
    const std::string g(drive::to_string(c.verdict.grade));
    os << "<tr class=\"" << html_class(g) << "\"><td><code>" << markup_escape(c.spec->id)
       << "</code> " << markup_escape(c.spec->section) << ": " << markup_escape(c.spec->title)
       << "<br><small>" << markup_escape(c.spec->source) << "</small></td><td>" << g << "</td><td>"
       << markup_escape(c.spec->good) << "</td><td>" << markup_escape(c.verdict.reason);
    if (!c.verdict.checks.empty()) {
      os << "<details><summary>checks (" << c.verdict.checks.size() << ")</summary><pre>";
      for (const drive::Check& ch : c.verdict.checks)
        os << (ch.ok ? "ok   " : "FAIL ") << markup_escape(ch.name) << ": "
           << markup_escape(ch.detail) << "\n";
      os << "</pre></details>";
    }
    if (!c.diagnoses.empty()) {
      os << "<br><small>topdump:";
      for (const drive::Diagnosis& d : c.diagnoses) os << " " << markup_escape(d.code);
      os << "</small>";
    }
    os << "</td><td>";
    if (!c.capture.empty())
      os << "<a href=\"" << markup_escape(to + c.capture) << "\">capture</a> <a href=\""
         << markup_escape(to + c.stderr_path) << "\">stderr</a>";
    os << "</td></tr>\n";
  }
  os << "</table>\n</body></html>\n";
}

std::string drive_table_input_error(const nlohmann::json& report) {
  if (!report.is_object() || report.value("tool", "") != "topconf drive")
    return "not a topconf drive report";
  if (!report.contains("cases") || !report["cases"].is_array()) return "no cases";
  return {};
}

nlohmann::json drive_table_json(const std::vector<TableInput>& inputs) {
  nlohmann::json t = {{"tool", "topconf drive"}, {"kind", "table"}};
  t["columns"] = nlohmann::json::array();
  std::map<std::string, std::size_t> row_of;
  nlohmann::json rows = nlohmann::json::array();
  // Rows in the case table's order, whatever the reports hold.
  for (const drive::CaseSpec& c : drive::cases()) {
    row_of[std::string(c.id)] = rows.size();
    rows.push_back({{"id", c.id},
                    {"section", c.section},
                    {"title", c.title},
                    {"cells", nlohmann::json::array()}});
  }
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const nlohmann::json& r = inputs[i].report;
    t["columns"].push_back({{"file", inputs[i].file},
                            {"agent", r.value("agent", "")},
                            {"model", r.value("model", "")},
                            {"link", r.value("link", "")},
                            {"exec", r.value("exec", "")},
                            {"summary", r.value("summary", nlohmann::json::object())},
                            {"exit_code", r.value("exit_code", -1)}});
    for (const auto& k : r["cases"]) {
      const auto it = row_of.find(k.value("id", ""));
      if (it == row_of.end()) continue;
      rows[it->second]["cells"].push_back({{"column", i},
                                           {"grade", k.value("grade", "")},
                                           {"reason", k.value("reason", "")},
                                           {"folder", k.value("folder", "")}});
    }
  }
  t["rows"] = rows;
  return t;
}

void write_drive_table_html(std::ostream& os, const nlohmann::json& t) {
  const nlohmann::json& cols = t["columns"];
  std::vector<TableColumnTop> tops;
  for (const auto& c : cols) {
    const int code = c.value("exit_code", -1);
    tops.push_back({.head_html = markup_escape(c.value("agent", "")) + "<br><small>" +
                                 markup_escape(c.value("model", "")) + " over " +
                                 markup_escape(c.value("link", "")) + "</small>",
                    .summary_class = code == 0   ? "pass"
                                     : code == 1 ? "fail"
                                                 : "error",
                    .summary_html = "<b>exit " + std::to_string(code) + "</b>"});
  }
  write_table_page_top(os, "topconf drive: agents",
                       "topconf drive: " + std::to_string(cols.size()) + " agent(s)",
                       "One column per driver run, one row per case (stable IDs, docs/DRIVE.md); "
                       "a cell is the case's grade, its reason the tooltip, linking the case's "
                       "folder.",
                       "case", "exit", tops);
  std::string section;
  for (const auto& row : t["rows"]) {
    if (row.value("section", "") != section) {
      section = row.value("section", "");
      os << "<tr><th colspan=\"" << cols.size() + 1 << "\">" << markup_escape(section)
         << "</th></tr>\n";
    }
    os << "<tr><td><code>" << markup_escape(row.value("id", "")) << "</code> "
       << markup_escape(row.value("title", "")) << "</td>";
    std::vector<const nlohmann::json*> by_col(cols.size(), nullptr);
    for (const auto& cell : row["cells"]) by_col[cell.value("column", 0u)] = &cell;
    for (std::size_t i = 0; i < by_col.size(); ++i) {
      const nlohmann::json* cell = by_col[i];
      if (!cell) {
        os << "<td class=\"na\">-</td>";
        continue;
      }
      const std::string g = cell->value("grade", "");
      // The folder is relative to the agent's own run directory.
      const std::string href =
          "agents/" + cols[i].value("agent", "") + "/" + cell->value("folder", "");
      os << "<td class=\"" << html_class(g) << "\" title=\""
         << markup_escape(cell->value("reason", "")) << "\"><a href=\"" << markup_escape(href)
         << "\">" << markup_escape(g) << "</a></td>";
    }
    os << "</tr>\n";
  }
  os << "</table>\n</body></html>\n";
}

}  // namespace topconf
