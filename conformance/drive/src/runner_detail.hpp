// What the per-case runner and the persistent mode share (private to drive/).
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "drive/runner.hpp"
#include "process.hpp"

namespace topconf::drive::detail {

// The driver's environment: TOPCONF_CASE, _INTENT, _MODEL, _LINK, _DURATION,
// the link's TOPCONF_PTY, _HOST, _PORT, and TOPCONF_T0_US: time 0 (`t0`,
// when the driver is started) on CLOCK_MONOTONIC, in microseconds.
std::vector<std::pair<std::string, std::string>> environment(
    const DriveOptions& o, const std::string& case_id, const std::string& intents,
    const std::vector<std::pair<std::string, std::string>>& link, double duration,
    std::chrono::steady_clock::time_point t0);
// Whether the driver exited at once (`t` s after its start): within 0.2 s,
// or with the shell's 126/127 (cannot run) at any time.
bool at_once(DriverProcess& p, double t);
// The last 300 bytes of a file (the driver's stderr).
std::string tail_of(const std::string& path);
// Grades `r` into `res` and writes the case's truth.csv.
void finish(const DriveOptions& o, const CaseSpec& c, const CaseSetup& setup, Record& r,
            CaseResult& res);
// --persistent: one link, one driver, the cases one after another.
void run_persistent(const DriveOptions& o, DriveRun& run);

}  // namespace topconf::drive::detail
