// topconf's outputs: console table and summary, JSON with transcripts,
// JUnit XML and a self-contained HTML report.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "conf/runner.hpp"

namespace topconf {

void write_console(std::ostream& os, const RunResult& r, bool color);
nlohmann::json to_json(const RunResult& r);
void write_junit(std::ostream& os, const RunResult& r);
void write_html(std::ostream& os, const RunResult& r);
// The page head every topconf HTML report shares (its style sheet; the
// classes pass, non-strict, fail, error, inconclusive, na and sum), up to
// and including <body>.
void write_html_head(std::ostream& os, std::string_view title);
// Printable form of frame bytes, as topdump shows them (top::escape): \r,
// \n and \\, other non-printables as \xHH.
std::string printable(std::string_view bytes);

}  // namespace topconf
