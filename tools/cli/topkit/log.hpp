// spdlog for a tool's messages on stderr, in the one format of
// topkit/cli.hpp: "TOOL: LEVEL: MESSAGE" ("topconf: error: ..."), no
// timestamp; the level's name coloured on a terminal.
#pragma once

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <string>

namespace topkit::cli {

inline void use_stderr_log(const std::string& tool) {
  auto logger = spdlog::stderr_color_mt(tool);
  logger->set_pattern("%n: %^%l%$: %v");
  spdlog::set_default_logger(std::move(logger));
}

}  // namespace topkit::cli
