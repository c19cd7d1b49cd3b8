// Capture times: microseconds since the epoch, read from and written as
// ISO 8601.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace topdump {

// Current time in microseconds since the epoch.
std::int64_t now_us();

// Parses "2024-05-01T12:00:00.123Z", "...+02:00", or plain epoch seconds
// ("1714564800.5"); microseconds since the epoch.
std::optional<std::int64_t> parse_time(std::string_view s);
// "2024-05-01T12:00:00.123456Z" ("-" for kNoTime)
std::string format_time(std::int64_t us);

}  // namespace topdump
