// Writes docs/CATALOG.md from the command catalog: every command of both
// documents with its forms and field layouts. tests/CMakeLists.txt checks
// that the committed file is up to date; regenerate with
//   ./build/default/tools/catalog_md > docs/CATALOG.md
#include <cstdio>
#include <string>

#include "markdown.hpp"
#include "top/top.hpp"

using mdtable::cell;

namespace {

std::string models(top::ModelSet m) {
  std::string s;
  for (top::Model x : top::all_models())
    if (m & top::model_bit(x)) {
      if (!s.empty()) s += " ";
      s += top::to_string(x);
    }
  return s;
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

}  // namespace

int main() {
  std::printf("# Command catalog\n\n");
  std::printf(
      "Generated from `protocol/src/catalog_*.cpp` by `tools/catalog_md.cpp`; do not edit.\n"
      "Widths are in characters (bytes for binary fields); width 0 is the rest of the data.\n"
      "Values are `raw * scale` in the unit given; ranges are in that unit.\n"
      "Commands and forms of the field (neither document gives them) name their source;\n"
      "topsim's document profile does not take them (docs/FIELD.md).\n\n");
  for (top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek}) {
    auto cmds = top::commands(d);
    std::printf("## %s (%zu commands)\n\n", d == top::Dialect::skydroid ? "SkyDroid" : "Topotek",
                cmds.size());
    for (const top::CommandSpec& c : cmds) {
      std::printf("### %.*s: %s\n\n", static_cast<int>(c.ident.size()), c.ident.data(),
                  std::string(c.title).c_str());
      std::printf("%s; address class %c; models: %s.", std::string(c.section).c_str(), c.address,
                  models(c.models).c_str());
      if (!c.note.empty()) std::printf(" %s.", std::string(c.note).c_str());
      if (c.from_field())
        std::printf(" Neither document lists it; field evidence: %s.",
                    std::string(c.evidence).c_str());
      std::printf("\n\n");
      for (const top::FormSpec& f : c.forms) {
        std::printf(
            "- `%c` %s, data length %u%s%s%s\n", f.control,
            std::string(top::to_string(f.role)).c_str(), f.min_length,
            f.min_length == f.max_length ? "" : ("-" + std::to_string(f.max_length)).c_str(),
            f.note.empty() ? "" : ": ", std::string(f.note).c_str());
        if (f.from_field() && !c.from_field())
          std::printf("  - field form, not the document's: %s\n", cell(f.evidence).c_str());
        auto field = [&](const top::FieldSpec& s, const char* indent) {
          std::string line = std::string(indent) + "- `" + std::string(s.name) + "` " +
                             std::string(top::to_string(s.kind)) + " width " +
                             std::to_string(s.width);
          if (s.scale != 1.0) line += " scale " + num(s.scale);
          if (!s.unit.empty()) line += " unit " + std::string(s.unit);
          if (s.min <= s.max) line += " range [" + num(s.min) + ", " + num(s.max) + "]";
          if (!s.none.empty()) line += " none `" + std::string(s.none) + "`";
          if (!s.enums.empty()) {
            line += " values:";
            for (const auto& e : s.enums) {
              char b[16];
              if (s.kind == top::FieldKind::enum_char)
                std::snprintf(b, sizeof b, "'%c'", static_cast<char>(e.value));
              else
                std::snprintf(b, sizeof b, "%02llX", static_cast<unsigned long long>(e.value));
              line += std::string(" ") + b + "=" + std::string(e.name);
            }
          }
          if (!s.note.empty()) line += " (" + cell(s.note) + ")";
          std::printf("%s\n", line.c_str());
        };
        for (const top::FieldSpec& s : f.fields) field(s, "  ");
        if (!f.record.empty()) {
          // a form with records (the Topotek ODR): as many as its last field says
          std::printf("  - then `%s` records (fields `name[n]`, n from 1), each:\n",
                      std::string(f.fields.back().name).c_str());
          for (const top::FieldSpec& s : f.record) field(s, "    ");
        }
      }
      std::printf("\n");
    }
  }
  return 0;
}
