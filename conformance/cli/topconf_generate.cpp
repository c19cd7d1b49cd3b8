// topconf generate: a model's default matrix, from the catalog.
#include <iostream>

#include "commands.hpp"
#include "conf/generate.hpp"
#include "topkit/model.hpp"

namespace topconf::cli {

namespace {

class GenerateCommand : public topkit::cli::Subcommand {
 public:
  explicit GenerateCommand(CLI::App& app);
  int run() override;

 private:
  std::string model_name_, out_;
};

}  // namespace

GenerateCommand::GenerateCommand(CLI::App& app)
    : Subcommand(app, "generate", "write a model's default matrix generated from the catalog") {
  sub_->add_option("--model", model_name_, top::model_list("|", "|"))->required();
  sub_->add_option("-o,--output", out_, "output file (default: stdout)");
}

int GenerateCommand::run() {
  const auto m = topkit::cli::model_arg(kTool, model_name_);
  if (!m) return 2;
  const std::string text = generate_matrix(*m).dump(2) + "\n";
  if (out_.empty()) {
    std::cout << text;
    return 0;
  }
  return write_output(out_, [&](std::ostream& o) { o << text; }) ? 0 : 2;
}

std::unique_ptr<topkit::cli::Subcommand> generate_command(CLI::App& app) {
  return std::make_unique<GenerateCommand>(app);
}

}  // namespace topconf::cli
