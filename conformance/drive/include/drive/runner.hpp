// topconf drive's runner (docs/DRIVE.md): per case a fresh topsim device on
// a fresh link, the driver under test started with --exec, its intents,
// its beliefs, the device's truth and the wire recorded, then graded.
// Cases run concurrently; --persistent keeps one driver and one link.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "drive/grade.hpp"

namespace topconf::drive {

struct DriveOptions {
  top::Model model = top::Model::sip;
  topsim::TransportKind link = topsim::TransportKind::pty;
  std::string exec;
  std::vector<const CaseSpec*> cases;  // in ID order
  bool full = false;
  unsigned jobs = 8;
  bool persistent = false;
  std::string agent;
  std::string out_dir = "drive-out";
  std::uint64_t seed = 1;
  // topdump, for the diagnoses of each case's capture: empty to look next
  // to this program, then in ../analyzer/, then on PATH.
  std::string topdump;
  // Told of each case once graded (from the thread that ran it).
  std::function<void(const struct CaseResult&)> on_case;
};

struct Diagnosis {
  std::string code, severity, message;
};

struct CaseResult {
  const CaseSpec* spec = nullptr;
  Verdict verdict;
  double duration_s = 0;
  std::string folder, capture, stderr_path;  // relative to out_dir
  std::string driver_exit;                   // "signal 15", "exit 0", ...
  std::size_t beliefs = 0, non_json_lines = 0;
  std::vector<std::string> errors;  // the beliefs' error texts
  std::vector<Diagnosis> diagnoses;
  std::string diagnoses_note;  // why there are none (no topdump)
  double started_s = 0;        // --persistent: when the case began in the driver's time
};

struct DriveRun {
  DriveOptions options;
  std::string started;  // ISO 8601 UTC
  double seconds = 0;
  std::vector<CaseResult> cases;
  std::string error;  // the run could not happen (exit 2)
  int exit_code() const;
  std::size_t count(Grade g) const;
};

// Runs every case of `o`; never throws (errors land in the run or its cases).
DriveRun run_drive(const DriveOptions& o);

// The link names ("pty", "udp", "tcp").
std::string_view to_string(topsim::TransportKind k) noexcept;

}  // namespace topconf::drive
