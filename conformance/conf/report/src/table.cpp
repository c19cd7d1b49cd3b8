#include "conf/table.hpp"

#include <algorithm>
#include <map>

#include "conf/report.hpp"
#include "top/detail/text.hpp"

namespace topconf {

using top::markup_escape;

namespace {

constexpr const char* kGrades[] = {"must", "should", "info"};

// The column of one report: what was tested (firmware, model, target), by
// which driver, its verdict and capture.
nlohmann::json column_of(const TableInput& in) {
  const nlohmann::json& r = in.report;
  const nlohmann::json& c = r["compatibility"];
  const std::string model = r.value("model", "");
  nlohmann::json col;
  col["file"] = in.file;
  col["firmware"] = r.value("firmware", model);
  col["model"] = model;
  col["target"] = r.value("target", "");
  col["driver"] = c.value("driver", "");
  col["verdict"] = c.value("verdict", "");
  col["text"] = c.value("text", "");
  col["exit_code"] = r.value("exit_code", -1);
  if (r.contains("capture")) col["capture"] = r["capture"];
  return col;
}

// The HTML class of a cell's or a column's verdict (write_html_head's).
std::string cell_class(const nlohmann::json& cell) {
  const std::string res = cell.value("result", "");
  if (res == "pass" || res == "non-strict") return res;
  if (res == "not applicable") return "na";
  return cell.value("grade", "") == "info" ? "na" : "fail";
}

std::string verdict_class(const std::string& v) {
  return v == "compatible" ? "pass" : v == "compatible without" ? "non-strict" : "fail";
}

}  // namespace

std::string table_input_error(const nlohmann::json& report) {
  if (!report.is_object() || report.value("tool", "") != "topconf")
    return "not a topconf run report";
  if (!report.contains("compatibility") || !report["compatibility"].is_object())
    return "no compatibility object: not a topconf run --driver report";
  if (!report["compatibility"].contains("needs") || !report["compatibility"]["needs"].is_array())
    return "its compatibility object has no needs";
  return {};
}

nlohmann::json table_json(const std::vector<TableInput>& inputs) {
  nlohmann::json t;
  t["tool"] = "topconf";
  t["kind"] = "table";
  t["columns"] = nlohmann::json::array();
  // Rows by grade, then in first-seen order; a case's cell per column.
  std::vector<std::string> order;
  std::map<std::string, nlohmann::json> rows;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const nlohmann::json col = column_of(inputs[i]);
    t["columns"].push_back(col);
    std::map<std::string, const nlohmann::json*> cases;
    const nlohmann::json& report = inputs[i].report;
    if (report.contains("cases") && report["cases"].is_array())
      for (const auto& k : report["cases"]) cases[k.value("id", "")] = &k;
    for (const auto& n : inputs[i].report["compatibility"]["needs"]) {
      const std::string id = n.value("case", "");
      if (!rows.count(id)) {
        order.push_back(id);
        rows[id] = {{"case", id},
                    {"grade", n.value("grade", "")},
                    {"feature", n.value("feature", "")},
                    {"cells", nlohmann::json::array()}};
      }
      nlohmann::json cell = {{"column", i},
                             {"result", n.value("result", "")},
                             {"served", n.value("served", false)},
                             {"grade", n.value("grade", "")},
                             {"outcome", n.value("outcome", "")}};
      if (const auto it = cases.find(id); it != cases.end()) {
        cell["reason"] = it->second->value("reason", "");
        cell["start_ms"] = it->second->value("start_ms", 0.0);
        cell["duration_ms"] = it->second->value("duration_ms", 0.0);
      }
      if (col.contains("capture")) cell["capture"] = col["capture"];
      rows[id]["cells"].push_back(cell);
    }
  }
  t["groups"] = nlohmann::json::array();
  for (const char* g : kGrades) {
    nlohmann::json group = {{"grade", g}, {"rows", nlohmann::json::array()}};
    for (const std::string& id : order)
      if (rows[id].value("grade", "") == g) group["rows"].push_back(rows[id]);
    if (!group["rows"].empty()) t["groups"].push_back(group);
  }
  return t;
}

void write_table_html(std::ostream& os, const nlohmann::json& t) {
  const nlohmann::json& cols = t["columns"];
  std::vector<TableColumnTop> tops;
  for (const auto& c : cols)
    tops.push_back({.head_html = markup_escape(c.value("firmware", "")) + "<br><small>" +
                                 markup_escape(c.value("target", "")) + "</small><br>x <code>" +
                                 markup_escape(c.value("driver", "")) + "</code>",
                    .summary_class = std::string(verdict_class(c.value("verdict", ""))),
                    .summary_html = "<b>" + markup_escape(c.value("text", "")) + "</b>"});
  write_table_page_top(os, "topconf compatibility table", "Driver compatibility",
                       std::to_string(cols.size()) +
                           " run(s) of <code>topconf run --driver</code>: firmware x driver. A "
                           "cell is the graded verdict of the driver's need on that firmware; it "
                           "links the run's capture when the report names one.",
                       "need", "verdict", tops);
  for (const auto& g : t["groups"]) {
    os << "<tr><th colspan=\"" << cols.size() + 1 << "\">" << markup_escape(g.value("grade", ""))
       << "</th></tr>\n";
    for (const auto& row : g["rows"]) {
      os << "<tr><td><code>" << markup_escape(row.value("case", "")) << "</code><br>"
         << markup_escape(row.value("feature", "")) << "</td>";
      std::vector<const nlohmann::json*> by_col(cols.size(), nullptr);
      for (const auto& cell : row["cells"]) by_col[cell.value("column", 0u)] = &cell;
      for (const nlohmann::json* cell : by_col) {
        if (!cell) {
          os << "<td class=\"na\">-</td>";
          continue;
        }
        const std::string res = cell->value("result", "");
        os << "<td class=\"" << cell_class(*cell) << "\" title=\""
           << markup_escape(cell->value("outcome", "")) << "\">";
        if (cell->contains("capture"))
          os << "<a href=\"" << markup_escape((*cell)["capture"].get<std::string>()) << "\">"
             << markup_escape(res) << "</a>";
        else
          os << markup_escape(res);
        if (cell->contains("start_ms"))
          os << "<br><small>at " << static_cast<long long>(cell->value("start_ms", 0.0))
             << " ms</small>";
        os << "</td>";
      }
      os << "</tr>\n";
    }
  }
  os << "</table>\n</body></html>\n";
}

}  // namespace topconf
