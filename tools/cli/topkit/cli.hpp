// What topdump, topsim and topconf do alike on their command line: a
// --version flag, exit status 2 for every usage error (CLI11's own codes
// are 100-115), an unknown subcommand named, option defaults shown in
// --help (and so in the man pages generated from it, docs/man/), and a
// failed write to stdout turned into exit status 2.
#pragma once

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#ifndef TOPKIT_VERSION
#error "TOPKIT_VERSION is defined by CMake (the project's version)"
#endif

namespace topkit::cli {

// --version ("topdump 0.1.0") and defaults shown in --help.
inline void setup_app(CLI::App& app, const std::string& tool) {
  app.name(tool);
  app.set_version_flag("--version", tool + " " + TOPKIT_VERSION, "print the version and exit");
  app.option_defaults()->always_capture_default();
  app.get_formatter()->column_width(34);
}

// Parses the command line. Returns -1 to go on, or the exit status: 0 after
// --help or --version, 2 on bad usage (with CLI11's message, and for a word
// where a subcommand belongs, the subcommands there are).
inline int parse_or_exit(CLI::App& app, int argc, char** argv) {
  if (app.get_require_subcommand_min() > 0 && argc > 1 && argv[1][0] == '-') {
    // CLI11 would only say that a subcommand is required
    std::string opt = argv[1];
    opt = opt.substr(0, opt.find('='));
    if (!app.get_option_no_throw(opt)) {
      std::fprintf(stderr, "%s: unknown option \"%s\" (--help for more)\n", app.get_name().c_str(),
                   opt.c_str());
      return 2;
    }
  }
  if (app.get_require_subcommand_min() > 0 && argc > 1 && argv[1][0] != '-') {
    const std::string word = argv[1];
    std::string names;
    bool known = false;
    for (const CLI::App* s : app.get_subcommands({})) {
      known = known || s->check_name(word);
      names += (names.empty() ? "" : ", ") + s->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "%s: unknown subcommand \"%s\" (one of %s; --help for more)\n",
                   app.get_name().c_str(), word.c_str(), names.c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  return -1;
}

// Flushes stdout (C and C++ streams) and returns `rc`, or 2 with a message
// when anything written to it was lost (a full disk, a closed pipe).
inline int close_stdout(const std::string& tool, int rc) {
  std::cout.flush();
  errno = 0;
  const bool bad = std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout;
  if (bad) {
    const int e = errno;
    std::fprintf(stderr, "%s: write error on standard output%s%s\n", tool.c_str(), e ? ": " : "",
                 e ? std::strerror(e) : "");
    return 2;
  }
  return rc;
}

}  // namespace topkit::cli
