// topconf models: the catalog's models, one per line.
#include <iostream>

#include "commands.hpp"
#include "topkit/model.hpp"

namespace topconf::cli {

namespace {

class ModelsCommand : public topkit::cli::Subcommand {
 public:
  explicit ModelsCommand(CLI::App& app);
  int run() override;

 private:
  bool paths_ = false;
};

}  // namespace

ModelsCommand::ModelsCommand(CLI::App& app)
    : Subcommand(app, "models", "list the models, one per line (the catalog's)") {
  sub_->add_flag("--paths", paths_, "with the default matrix of each, where topconf looks for it");
}

int ModelsCommand::run() {
  for (const std::string& m : topkit::cli::model_names()) {
    std::cout << m;
    if (paths_) std::cout << " " << matrix_dir() << "/" << m << ".json";
    std::cout << "\n";
  }
  return 0;
}

std::unique_ptr<topkit::cli::Subcommand> models_command(CLI::App& app) {
  return std::make_unique<ModelsCommand>(app);
}

}  // namespace topconf::cli
