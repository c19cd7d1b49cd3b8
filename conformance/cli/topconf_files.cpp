// What topconf's subcommands share: the matrix files, and writing outputs.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "conf/generate.hpp"
#include "topkit/model.hpp"

#ifndef TOPKIT_MATRIX_RELDIR
#error "TOPKIT_MATRIX_RELDIR (the matrices relative to the binary) is defined by CMake"
#endif

namespace topconf::cli {

namespace {

// The directory of the running binary ("" when unknown).
std::string exe_dir() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return {};
  const std::string path(buf, static_cast<std::size_t>(n));
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

}  // namespace

std::string matrix_dir() {
  if (const char* e = std::getenv("TOPCONF_MATRIX_DIR")) return e;
  const std::string dir = exe_dir();
  return (dir.empty() ? std::string(".") : dir) + "/" + TOPKIT_MATRIX_RELDIR;
}

std::optional<std::string> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool write_output(const std::string& path, const std::function<void(std::ostream&)>& f) {
  std::ofstream out(path, std::ios::binary);
  if (!out) {
    spdlog::error("{}: cannot write", path);
    return false;
  }
  f(out);
  out.close();
  if (out.fail()) spdlog::error("{}: write error", path);
  return !out.fail();
}

std::optional<int> load_run_matrix(const std::string& model_name, const std::string& matrix_path,
                                   Matrix& out) {
  const auto model = topkit::cli::model_arg(kTool, model_name);
  if (!model) return 2;
  std::string file = matrix_path;
  std::optional<std::string> text;
  if (file.empty()) {
    file = matrix_dir() + "/" + model_name + ".json";
    text = read_file(file);
    if (!text) {
      spdlog::warn("{}: not found; generating the default matrix from the catalog", file);
      text = generate_matrix(*model).dump();
      file = "(generated " + model_name + ")";
    }
  } else if (!(text = read_file(file))) {
    spdlog::error("{}: cannot read", file);
    return 2;
  }
  auto loaded = load_matrix(*text, file);
  if (!loaded.matrix) {
    for (const auto& e : loaded.errors) std::cerr << e << "\n";
    return 2;
  }
  out = std::move(*loaded.matrix);
  if (out.model != *model)
    spdlog::warn("{} is written for {}; running it as {}", file, top::to_string(out.model),
                 model_name);
  out.model = *model;
  out.dialect = top::dialect_of(*model);
  return std::nullopt;
}

}  // namespace topconf::cli
