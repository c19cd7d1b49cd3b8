// Helpers shared by the conformance tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "conf/matrix.hpp"

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::string matrix_path(std::string_view model) {
  return std::string(TOPKIT_SOURCE_DIR) + "/conformance/matrices/" + std::string(model) + ".json";
}

inline topconf::Matrix default_matrix(top::Model m) {
  const std::string path = matrix_path(top::to_string(m));
  auto r = topconf::load_matrix(read_text(path), path);
  if (!r.matrix) throw std::runtime_error(r.errors.empty() ? path : r.errors[0]);
  return *r.matrix;
}
