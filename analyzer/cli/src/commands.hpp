// topdump's subcommands, one file each (<name>_cmd.cpp), in the one pattern
// of topkit/cli.hpp (a Subcommand, best an OwnSubcommand that holds only
// its own options): options added when it is made, run() when the command
// line chose it, returning the exit status: 0 no error finding, 1 an error
// finding, 2 unreadable input, a failed write or bad usage. Messages about
// a failure are in the one format ("topdump: error: ...").
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "top/catalog.hpp"
#include "topkit/cli.hpp"

namespace topdump {

inline constexpr const char* kTool = "topdump";

// "topdump: error: MESSAGE" on stderr.
inline void error(const std::string& message) { topkit::cli::error(kTool, message); }

// --dialect and --model, with these helps.
void add_dialect_model(CLI::App* sub, std::string& dialect, const std::string& dialect_help,
                       std::string& model, const std::string& model_help);

// --dialect and --model ("auto" or a name) as one setting: each checked by
// the one check of a named value (topkit::cli::one_of), then that the model
// speaks the dialect. False after the message.
bool dialect_and_model(const std::string& dialect, const std::string& model, top::Dialect& d,
                       top::Model& m);

// The subcommands, each defined in its file (<name>_cmd.cpp); main() adds
// them in its order.
topkit::cli::SubcommandFactory read_command, stats_command, frame_command, live_command,
    serial_command, report_command, wireshark_command;

}  // namespace topdump
