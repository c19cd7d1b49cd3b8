// What topdump, topsim and topconf do alike on their command line: a
// --version flag, exit status 2 for every usage error (CLI11's own codes
// are 100-115), an unknown subcommand named, option defaults shown in
// --help (and so in the man pages generated from it, docs/man/), and a
// failed write to stdout turned into exit status 2. parse(), error(),
// one_of() and Subcommand give the three tools one error format
// ("TOOL: error: ..."), one check of a named value and one subcommand
// pattern; topkit/log.hpp points spdlog at the same format.
#pragma once

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

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

// What is wrong with the first word of a command line whose tool needs a
// subcommand, before CLI11 sees it (CLI11 would only say that a subcommand
// is required): an unknown option, or a word that names no subcommand (with
// the subcommands there are). Empty when nothing is.
inline std::string subcommand_problem(CLI::App& app, int argc, char** argv) {
  if (app.get_require_subcommand_min() == 0 || argc < 2) return {};
  if (argv[1][0] == '-') {
    std::string opt = argv[1];
    opt = opt.substr(0, opt.find('='));
    if (app.get_option_no_throw(opt)) return {};
    return "unknown option \"" + opt + "\" (--help for more)";
  }
  const std::string word = argv[1];
  std::string names;
  bool known = false;
  for (const CLI::App* s : app.get_subcommands({})) {
    known = known || s->check_name(word);
    names += (names.empty() ? "" : ", ") + s->get_name();
  }
  if (known) return {};
  return "unknown subcommand \"" + word + "\" (one of " + names + "; --help for more)";
}

// ---------------------------------------------------------------------------
// The one error format, the one parse, the one subcommand pattern.

// "TOOL: error: MESSAGE" on stderr: the format of every message a tool
// writes about a failure (no timestamp; topkit/log.hpp sets spdlog to it).
inline void error(const std::string& tool, const std::string& message) {
  std::fprintf(stderr, "%s: error: %s\n", tool.c_str(), message.c_str());
}

// "TOOL: warning: MESSAGE" on stderr: the same format for what went wrong
// without failing the run.
inline void warning(const std::string& tool, const std::string& message) {
  std::fprintf(stderr, "%s: warning: %s\n", tool.c_str(), message.c_str());
}

// Flushes stdout (C and C++ streams) and returns `rc`, or 2 with a message
// when anything written to it was lost (a full disk, a closed pipe).
inline int close_stdout(const std::string& tool, int rc) {
  std::cout.flush();
  errno = 0;
  const bool bad = std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout;
  if (bad) {
    const int e = errno;
    error(tool, std::string("write error on standard output") + (e ? ": " : "") +
                    (e ? std::strerror(e) : ""));
    return 2;
  }
  return rc;
}

// The index of `value` in `names`, or none with "TOOL: error: OPTION VALUE:
// not one of A, B, C" (the one check of an option whose value names one of
// a list: a model, a level, an enum).
inline std::optional<std::size_t> one_of(const std::string& tool, const std::string& option,
                                         const std::string& value,
                                         const std::vector<std::string>& names) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == value) return i;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  error(tool, option + " " + value + ": not one of " + list);
  return std::nullopt;
}

// Parses the command line. Returns -1 to go on, or the exit status: 0 after
// --help or --version (stdout checked), 2 on bad usage, with every usage
// error in the one format ("TOOL: error: ..."; for a word where a
// subcommand belongs, the subcommands there are).
inline int parse(CLI::App& app, int argc, char** argv) {
  const std::string tool = app.get_name();
  if (const std::string why = subcommand_problem(app, argc, argv); !why.empty()) {
    error(tool, why);
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version
    if (e.get_exit_code() == 0) return close_stdout(tool, app.exit(e));
    error(tool, std::string(e.what()) + " (--help for more)");
    return 2;
  }
  return -1;
}

// One subcommand: its options are added to the parent in the derived
// class's constructor; run() is called when the command line chose it.
// A subcommand is best written as an OwnSubcommand (below), which holds
// only what is its own.
class Subcommand {
 public:
  Subcommand(CLI::App& parent, const std::string& name, const std::string& help)
      : sub_(parent.add_subcommand(name, help)) {}
  virtual ~Subcommand() = default;
  Subcommand(const Subcommand&) = delete;
  Subcommand& operator=(const Subcommand&) = delete;
  bool selected() const { return sub_->parsed(); }
  // The exit status: 0, 1 (findings, failures) or 2.
  virtual int run() = 0;

 protected:
  CLI::App* sub_;
};

// The subcommand whose `Own` holds only what is the command's own: its
// options as members, declare(CLI::App&) adding them to the subcommand, and
// run() returning the exit status. `Own` is made from `args`.
//
//   struct Models {
//     bool paths = false;
//     void declare(CLI::App& sub) { sub.add_flag("--paths", paths, "..."); }
//     int run() const;
//   };
//   std::unique_ptr<topkit::cli::Subcommand> models_command(CLI::App& app) {
//     return topkit::cli::make_subcommand<Models>(app, "models", "list the models");
//   }
template <class Own>
class OwnSubcommand final : public Subcommand {
 public:
  template <class... Args>
  OwnSubcommand(CLI::App& parent, const std::string& name, const std::string& help, Args&&... args)
      : Subcommand(parent, name, help), own_(std::forward<Args>(args)...) {
    own_.declare(*sub_);
  }
  int run() override { return own_.run(); }

 private:
  Own own_;
};

template <class Own, class... Args>
std::unique_ptr<Subcommand> make_subcommand(CLI::App& parent, const std::string& name,
                                            const std::string& help, Args&&... args) {
  return std::make_unique<OwnSubcommand<Own>>(parent, name, help, std::forward<Args>(args)...);
}

// What each subcommand's file defines (as NAME_command): adds the
// subcommand to `parent`. A tool declares its factories once, in one
// declaration (its commands.hpp), and its main() hands them to run_tool.
using SubcommandFactory = std::unique_ptr<Subcommand>(CLI::App& parent);

// Runs the subcommand the command line chose and checks stdout after it.
inline int run_selected(const std::string& tool,
                        std::span<const std::unique_ptr<Subcommand>> subs) {
  for (const auto& s : subs)
    if (s->selected()) return close_stdout(tool, s->run());
  error(tool, "a subcommand is required (--help for more)");
  return 2;
}

// A tool's main() once `app` is set up: adds the subcommands of
// `factories` in their order (the order of --help), parses the command line
// and runs the subcommand it chose. Returns the exit status.
inline int run_tool(CLI::App& app, int argc, char** argv,
                    std::initializer_list<SubcommandFactory*> factories) {
  std::vector<std::unique_ptr<Subcommand>> subs;
  for (SubcommandFactory* f : factories) subs.push_back(f(app));
  if (int rc = parse(app, argc, argv); rc >= 0) return rc;
  return run_selected(app.get_name(), subs);
}

}  // namespace topkit::cli
