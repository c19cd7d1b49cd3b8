// topconf validate: matrix files against the schema rules.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>

#include "commands.hpp"

namespace topconf::cli {

namespace {

struct Validate {
  std::vector<std::string> files;
  void declare(CLI::App& sub) { sub.add_option("files", files, "matrix files")->required(); }
  int run() const;
};

int Validate::run() const {
  int rc = 0;
  for (const auto& f : files) {
    const auto text = read_file(f);
    if (!text) {
      spdlog::error("{}: cannot read", f);
      rc = 2;
      continue;
    }
    auto r = load_matrix(*text, f);
    for (const auto& e : r.errors) std::cerr << e << "\n";
    if (!r.errors.empty())
      rc = std::max(rc, 1);
    else
      std::cout << f << ": ok, " << r.matrix->cases.size() << " case(s)\n";
  }
  return rc;
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> validate_command(CLI::App& app) {
  return topkit::cli::make_subcommand<Validate>(app, "validate",
                                                "check matrix files against the schema rules");
}

}  // namespace topconf::cli
