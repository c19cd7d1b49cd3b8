// The time the topdump tests' made-up frames start at.
#pragma once

#include <cstdint>

namespace topdump {

inline constexpr std::int64_t kT0 = 1714564800LL * 1'000'000;  // 2024-05-01T12:00:00Z, in us

}  // namespace topdump
