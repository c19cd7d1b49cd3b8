// topconf fuzz: sends the generated and mutated cases of conf/fuzz_cases.hpp
// to a device over a Transport, checks after each case that it still
// answers (the matrix's probe), classifies what it answered, restarts it
// and minimises what broke it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "conf/fuzz_cases.hpp"
#include "conf/matrix.hpp"
#include "conf/transport.hpp"
#include "pcapio/writer.hpp"

namespace topconf {

// The failure classes, one JUnit testcase each.
enum class FailureClass : std::uint8_t {
  stopped,           // the device stopped answering (the probe failed)
  accepted_corrupt,  // it answered a frame whose checksum is wrong
  bad_reply,         // a malformed, wrongly addressed or out-of-range reply
  slow,              // an answer came later than --slow-ms after the case
  wrong_answer,      // ERE (or nothing) where the document promises an answer,
                     // or an answer where it promises ERE (must/should only)
};
inline constexpr FailureClass kFailureClasses[] = {
    FailureClass::stopped, FailureClass::accepted_corrupt, FailureClass::bad_reply,
    FailureClass::slow, FailureClass::wrong_answer};
std::string_view to_string(FailureClass c) noexcept;  // "stopped-answering", ...
std::string_view describe(FailureClass c) noexcept;   // one line

struct FuzzCaseResult {
  FuzzCase spec;
  std::optional<FailureClass> failure;
  std::string reason;
  std::vector<std::string> answers;  // frames attributed to the case
  std::uint64_t start_us = 0;        // since the start of the session
  std::uint64_t latency_us = 0;      // to the first answer (or the sync probe's)
};

// How a failure was reduced.
enum class MinimiseHow : std::uint8_t {
  alone,           // the case alone, after a restart, fails the same way
  window,          // only with cases before it: `cases` is the shrunk window
  not_reproduced,  // neither alone nor with the window
  skipped,         // no restart (--restart-cmd) for a device that stopped
};
std::string_view to_string(MinimiseHow h) noexcept;

struct FuzzFailure {
  std::uint64_t index = 0;
  FailureClass cls{};
  std::string reason;
  FuzzCase spec;
  std::vector<std::uint64_t> before;  // the cases sent just before it
  MinimiseHow how = MinimiseHow::skipped;
  std::vector<std::uint64_t> cases;  // the reproducer (in order)
  std::string frame;                 // one frame of the case that alone fails ("" if none)
  std::string note;
  bool restarted = false;
};

struct FuzzOptions {
  std::uint64_t seed = 1;
  std::uint64_t start = 0;
  std::optional<std::uint64_t> end;  // exclusive; none: until --duration or forever
  std::vector<std::uint64_t> only;   // --case: just these indices
  double duration_s = 0;             // 0: no limit
  double rate = 0;                   // cases/s; 0: as fast as the device answers
  std::uint32_t probe_every = 1;     // liveness probe every N cases
  std::uint32_t timeout_ms = 300;    // wait for a promised answer
  std::uint32_t slow_ms = 1000;
  std::uint32_t recover_ms = 3000;  // wait this long for the device to answer again
  std::function<bool()> restart;    // null: no restart (no --restart-cmd)
  bool minimise = true;
  std::size_t max_failures = 0;  // stop after this many (0: never)
  std::size_t window = 8;        // cases kept before a failure
  pcapio::Recorder* pcap = nullptr;
  std::function<void(const FuzzCaseResult&)> on_case;
  std::function<void(const FuzzFailure&)> on_failure;
  // Called about once a second: cases done, cases/s, failures so far.
  std::function<void(std::uint64_t, double, std::size_t)> on_progress;
};

struct FuzzResult {
  std::string target;
  top::Model model = top::Model::unknown;
  std::uint64_t seed = 0;
  std::uint64_t catalog_cases = 0;
  std::string started_at;
  double seconds = 0;
  std::uint64_t cases_run = 0;
  std::uint64_t next_index = 0;  // where --resume goes on
  std::uint64_t probes = 0;
  std::vector<FuzzFailure> failures;
  bool unusable = false;  // the target did not answer the probe at the start
  std::string unusable_reason;
  // "probe unanswered: VER": probes tried before the one the device answered
  // (conf/liveness.hpp); empty when none.
  std::string probe_note;
  bool aborted = false;  // the device stopped and could not be brought back
  std::string aborted_reason;
  double rate() const noexcept {
    return seconds > 0 ? static_cast<double>(cases_run) / seconds : 0;
  }
  // 0 no failure, 1 failures, 2 target unusable from the start.
  int exit_code() const noexcept;
};

// Runs the session. `m` gives the probe, its timeout and the levels.
FuzzResult run_fuzz(const Matrix& m, Transport& t, const FuzzOptions& o);

}  // namespace topconf
