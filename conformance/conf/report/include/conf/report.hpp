// topconf's outputs: console table and summary, JSON with transcripts,
// JUnit XML and a self-contained HTML report.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

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
// Printable form of frame bytes, as topdump shows them (top::escape): \r,
// \n and \\, other non-printables as \xHH.
std::string printable(std::string_view bytes);

}  // namespace topconf
