// topconf generate: a model's default matrix, from the catalog.
#include <iostream>

#include "commands.hpp"
#include "conf/generate.hpp"
#include "topkit/model.hpp"

namespace topconf::cli {

namespace {

struct Generate {
  std::string model_name, out;
  void declare(CLI::App& sub) {
    sub.add_option("--model", model_name, top::model_list("|", "|"))->required();
    sub.add_option("-o,--output", out, "output file (default: stdout)");
  }
  int run() const;
};

int Generate::run() const {
  const auto m = topkit::cli::model_arg(kTool, model_name);
  if (!m) return 2;
  const std::string text = generate_matrix(*m).dump(2) + "\n";
  if (out.empty()) {
    std::cout << text;
    return 0;
  }
  return write_output(out, [&](std::ostream& o) { o << text; }) ? 0 : 2;
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> generate_command(CLI::App& app) {
  return topkit::cli::make_subcommand<Generate>(
      app, "generate", "write a model's default matrix generated from the catalog");
}

}  // namespace topconf::cli
