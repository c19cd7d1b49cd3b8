// topconf's runner: executes a matrix over a Transport and classifies each
// case as pass, non-strict, fail, not-applicable, inconclusive or error.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "conf/matrix.hpp"
#include "conf/transport.hpp"
#include "pcapio/writer.hpp"

namespace topconf {

enum class Verdict : std::uint8_t { pass, non_strict, fail, not_applicable, inconclusive, error };
std::string_view to_string(Verdict v) noexcept;

// One line of a transcript: what was sent or received, and when (us since
// the start of the run, on the transport's clock).
struct Exchange {
  std::uint64_t t_us = 0;
  char dir = '>';  // '>' sent, '<' received, '!' runner note
  std::string bytes;
};

struct CaseResult {
  const Case* spec = nullptr;  // points into RunResult::matrix
  Verdict verdict = Verdict::error;
  bool flaky = false;  // passed after a failed attempt
  int attempts = 0;
  std::string reason;  // why it is not a plain pass
  // Non-strict only because the device answered in a form the field
  // records (top/device.hpp): the reason names the evidence, and the case
  // counts as passed for the exit status.
  bool field_form = false;
  std::vector<Exchange> transcript;
  std::uint64_t dropped_exchanges = 0;  // beyond the transcript cap
  std::uint64_t start_us = 0;
  std::uint64_t duration_us = 0;
  std::string started_at;  // ISO 8601 wall clock
};

struct RunOptions {
  std::vector<std::string> cases;           // ids or globs (*, ?); empty: all
  std::vector<std::string> tags;            // any of these; empty: all
  std::vector<Level> levels;                // empty: all
  std::optional<std::uint64_t> seed;        // shuffle the case order
  std::optional<std::uint32_t> retries;     // overrides the matrix
  std::optional<std::uint32_t> timeout_ms;  // overrides the matrix
  std::optional<std::uint32_t> settle_ms;   // overrides the matrix
  pcapio::Recorder* pcap = nullptr;
  std::function<void(const CaseResult&)> on_case;
  std::size_t max_transcript = 400;        // exchanges kept per case
  std::size_t max_frames_per_step = 4096;  // a flooding device is cut here
};

struct RunResult {
  std::shared_ptr<const Matrix> matrix;  // the run's own copy: specs point here
  std::string target;
  std::string matrix_file;
  top::Model model = top::Model::unknown;
  std::vector<CaseResult> cases;
  bool unreachable = false;
  std::string unreachable_reason;
  // "probe unanswered: VER": liveness probes the device left unanswered
  // although it is reachable (conf/liveness.hpp); empty when none.
  std::string probe_note;
  std::string started_at;
  double seconds = 0;  // wall time of the run
  std::uint64_t seed = 0;
  bool seeded = false;
  std::size_t count(Verdict v) const noexcept;
  // 0: every must/should case passed or is n/a; 1 otherwise; 2 unreachable.
  int exit_code() const noexcept;
};

RunResult run_matrix(const Matrix& m, Transport& t, const RunOptions& opts);

// The wall clock as ISO 8601 UTC with milliseconds ("2026-11-23T23:10:43.123Z").
std::string iso_now();

// Glob match for --case (* and ?).
bool glob_match(std::string_view pattern, std::string_view text) noexcept;

}  // namespace topconf
