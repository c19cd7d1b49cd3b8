// What the generated Markdown tables (docs/CATALOG.md, FIELD.md,
// DIAGNOSES.md) share: a cell's text, its '|' kept from splitting the row.
#pragma once

#include <string>
#include <string_view>

namespace mdtable {

inline std::string cell(std::string_view s) {
  std::string o;
  for (char c : s) o += c == '|' ? '/' : c;
  return o;
}

}  // namespace mdtable
