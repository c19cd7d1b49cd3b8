// topconf models: the catalog's models, one per line.
#include <iostream>

#include "commands.hpp"
#include "topkit/model.hpp"

namespace topconf::cli {

namespace {

struct Models {
  bool paths = false;
  void declare(CLI::App& sub) {
    sub.add_flag("--paths", paths, "with the default matrix of each, where topconf looks for it");
  }
  int run() const;
};

int Models::run() const {
  for (const std::string& m : topkit::cli::model_names()) {
    std::cout << m;
    if (paths) std::cout << " " << matrix_dir() << "/" << m << ".json";
    std::cout << "\n";
  }
  return 0;
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> models_command(CLI::App& app) {
  return topkit::cli::make_subcommand<Models>(app, "models",
                                              "list the models, one per line (the catalog's)");
}

}  // namespace topconf::cli
