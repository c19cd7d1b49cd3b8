// topconf validate: matrix files against the schema rules.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>

#include "commands.hpp"

namespace topconf::cli {

namespace {

class ValidateCommand : public topkit::cli::Subcommand {
 public:
  explicit ValidateCommand(CLI::App& app);
  int run() override;

 private:
  std::vector<std::string> files_;
};

}  // namespace

ValidateCommand::ValidateCommand(CLI::App& app)
    : Subcommand(app, "validate", "check matrix files against the schema rules") {
  sub_->add_option("files", files_, "matrix files")->required();
}

int ValidateCommand::run() {
  int rc = 0;
  for (const auto& f : files_) {
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

std::unique_ptr<topkit::cli::Subcommand> validate_command(CLI::App& app) {
  return std::make_unique<ValidateCommand>(app);
}

}  // namespace topconf::cli
