// topdump subcommands. Each add_* registers its options on the app and
// returns the function that runs it once parsed, returning the exit status:
// 0 no error finding, 1 an error finding, 2 unreadable input or bad usage.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace topdump {

using Run = std::function<int()>;

Run add_frame_command(CLI::App& app);
Run add_read_command(CLI::App& app);
Run add_stats_command(CLI::App& app);
Run add_live_command(CLI::App& app);
Run add_serial_command(CLI::App& app);

}  // namespace topdump
