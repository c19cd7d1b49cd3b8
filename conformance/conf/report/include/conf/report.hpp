// topconf's outputs: console table and summary, JSON with transcripts,
// JUnit XML and a self-contained HTML report.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "conf/runner.hpp"
#include "drivers/compat.hpp"

namespace topconf {

// With `compat` (topconf run --driver), each output also gives the
// driver's verdict (docs/COMPAT.md): the console's last line, the JSON's
// `compatibility` object and exit_code, a JUnit case, an HTML section.
void write_console(std::ostream& os, const RunResult& r, bool color,
                   const drivers::Compatibility* compat = nullptr);
nlohmann::json to_json(const RunResult& r, const drivers::Compatibility* compat = nullptr);
void write_junit(std::ostream& os, const RunResult& r,
                 const drivers::Compatibility* compat = nullptr);
void write_html(std::ostream& os, const RunResult& r,
                const drivers::Compatibility* compat = nullptr);
// The page head every topconf HTML report shares (its style sheet; the
// classes pass, non-strict, fail, error, inconclusive, na and sum), up to
// and including <body>.
void write_html_head(std::ostream& os, std::string_view title);
// A table page's top, for the tables of many runs (topconf table, drive
// --agent): the head, an <h1>, the intro paragraph, then the table's header
// row (`corner`, then a cell a column) and its summary row (`summary`, then
// each column's summary cell, of its class). HTML fields are written as given.
struct TableColumnTop {
  std::string head_html;
  std::string summary_class, summary_html;
};
void write_table_page_top(std::ostream& os, std::string_view title, std::string_view heading,
                          std::string_view intro_html, std::string_view corner,
                          std::string_view summary, const std::vector<TableColumnTop>& columns);
// Printable form of frame bytes, as topdump shows them (top::escape): \r,
// \n and \\, other non-printables as \xHH.
std::string printable(std::string_view bytes);

}  // namespace topconf
