// topdump report: a diagnosis of one or more captures as one self-contained
// HTML page (report_html.cpp, plots from report_svg.cpp) or as JSON
// (report_json.cpp). ReportSink collects what the Analyzer hands it (frames
// with their decoded fields, session notes, garbage); analyze() turns that
// and Analyzer::stats() into the Report: the gimbal's response to each
// angle command, the measured rate of each run of rate commands, latency,
// push streams, findings and unanswered requests. docs/REPORT.md describes
// every section and the JSON keys.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "session/analyzer.hpp"

namespace topdump::report {

struct Options {
  double tolerance_deg = 0.5;  // settled: the attitude stays within this of the target
  std::vector<std::string> files;
};

inline constexpr int kAxes = 3;                  // yaw, pitch, roll
const char* axis_name(int axis) noexcept;        // "yaw", "pitch", "roll"
inline constexpr std::size_t kExamples = 3;      // example frames per finding code
inline constexpr std::size_t kSlowest = 10;      // slowest exchanges kept
inline constexpr std::size_t kLatencyBins = 26;  // 0.1 ms .. 10 s, five per decade
// The lower edge of latency bin b in milliseconds (bin 0 also takes less).
double latency_bin_ms(std::size_t b) noexcept;

// The attitude reported by one identifier's frames (replies and pushes:
// every attitude row of top/motion.hpp, SkyDroid GAC, Topotek GAC, GIC and
// the field's GIA), up and right positive: each axis in its row's sign
// under its own convention (top::field_convention), so that a Topotek GIA
// pitch, down positive on the wire, plots and compares as up positive.
struct Attitude {
  const top::MotionSpec* spec = nullptr;
  std::vector<std::int64_t> t;
  std::array<std::vector<float>, kAxes> v;  // deg
  std::vector<std::int64_t> push_t;         // frames that answered no request
};

// Identifiers and enum names are the catalog's (static) strings.
struct AngleCommand {
  std::uint64_t frame = 0;
  std::int64_t t = 0;
  std::string_view ident;  // GAY, GAP, GAR, GAM, GIY...
  int axis = 0;
  float target = 0;         // deg, as commanded
  float speed = 0;          // deg/s from the command (0: none given)
  float min = 0, max = -1;  // the catalog's range for the dialect
  // This command and its refreshes: the same identifier, target and speed
  // again on the axis, nothing else moving it between (an angle, a rate, a
  // PTZ turn or centring; AP_Mount_Topotek
  // resends its GAY/GIP/GIR targets at 10 Hz, docs/FIELD.md: one target held,
  // judged once from the first).
  std::uint32_t commands = 1;
};

struct RateCommand {
  std::uint64_t frame = 0;
  std::int64_t t = 0;
  std::string_view ident;
  int axis = 0;
  std::int32_t steps = 0;  // raw value
  float rate = 0;          // deg/s by the catalog's scale
  float scale = 1;         // the catalog's deg/s per step
};

struct Mark {  // a command shown on the plot without a value (PTZ)
  std::uint64_t frame = 0;
  std::int64_t t = 0;
  std::string_view ident;
  std::string_view what;  // the PTZ action's name, or "bad checksum (dropped)"
};

struct ConvData {
  std::uint64_t id = 0;
  std::string a, b;
  Transport transport{};
  top::Dialect dialect = top::Dialect::unknown;
  std::uint64_t frames = 0;
  // The models whose catalog has every command the device sent (frames in
  // the response role with a good checksum), the command that last narrowed
  // them, and one the device sent that no model left has.
  top::ModelSet models = static_cast<top::ModelSet>(~0u);
  std::string_view narrowed_by, conflict;
  // The model the device named in its model-name reply (SkyDroid MOD;
  // top::model_named_by), which the diagnoses judge by too.
  top::Model named = top::Model::unknown;
  std::map<std::string, Attitude, std::less<>> attitude;  // by identifier: "GAC", "GIA"
  // deques: no copy as they grow, and stable addresses (AngleResult::cmd)
  std::deque<AngleCommand> angles;
  std::deque<RateCommand> rates;
  // Per axis, the angle command a refresh adds to (angles' index), or -1:
  // none, or another command came since.
  std::array<std::ptrdiff_t, kAxes> held{-1, -1, -1};
  std::deque<Mark> marks;
};

struct Example {
  std::uint64_t frame = 0;
  std::int64_t ts = kNoTime;
  std::uint64_t record = 0, offset = 0;  // where the frame sits in its capture
  std::uint32_t at = 0;                  // the finding's offset in the frame
  std::string file, from, to, raw, decoded, message;
};

struct CodeStat {
  std::string code;
  // The analyzer's code (findings/afindings.hpp; a diagnosis among them)
  // when it is one; none for a frame's finding (top::FindingCode).
  std::optional<ACode> acode;
  top::Severity severity{};
  std::uint64_t count = 0;
  std::int64_t first = kNoTime, last = kNoTime;
  std::map<std::string, std::uint64_t> senders;  // endpoint -> count
  std::vector<Example> examples;
};

// Event counts over time in at most kBins buckets: the bucket width
// doubles (merging pairs) when an event falls past the last one, so memory
// stays bounded whatever the capture's length.
class TimeHist {
 public:
  static constexpr std::size_t kBins = 2048;
  void add(std::int64_t ts);
  std::int64_t origin() const noexcept { return origin_; }
  std::int64_t width() const noexcept { return width_; }
  const std::vector<std::uint32_t>& counts() const noexcept { return counts_; }

 private:
  std::int64_t origin_ = kNoTime, width_ = 1000;
  std::vector<std::uint32_t> counts_;
};

struct Unanswered {
  std::int64_t ts = kNoTime;
  std::uint64_t frame = 0, conv = 0;
  std::string file, message;
  std::string ident;  // the request's identifier
  Cause cause = Cause::none;
};

// A diagnosis the session reported (a note whose code is a diagnosis):
// its case, for "What went wrong".
struct DiagnosisItem {
  top::Diagnosis code{};
  top::Severity severity{};
  std::int64_t ts = kNoTime, until = kNoTime;
  std::uint64_t frame = 0, count = 0, conv = 0;
  std::string file, message, ident;
};
inline constexpr std::size_t kMaxDiagnosisItems = 256;

struct Slow {
  std::int64_t latency_us = 0;
  std::uint64_t request = 0, response = 0, conv = 0;
  std::int64_t ts = kNoTime;
  std::string ident, response_raw;
};

// Collects the events of one run over every capture (set `file` before each).
class ReportSink : public Sink {
 public:
  void frame(const FrameEvent& e) override;
  void garbage(const GarbageEvent& e) override;
  void note(const NoteEvent& e) override;

  std::string file;
  std::vector<std::string> files;  // every file begun, in order
  std::map<std::uint64_t, ConvData> convs;
  std::map<std::string, CodeStat, std::less<>> codes;
  std::array<TimeHist, 3> finding_times;  // per severity
  std::vector<Unanswered> unanswered;
  std::vector<DiagnosisItem> diagnoses;  // at most kMaxDiagnosisItems
  std::uint64_t diagnoses_dropped = 0;
  std::map<std::string, std::array<std::uint64_t, kLatencyBins>, std::less<>> latency_bins;
  std::vector<Slow> slowest;  // a min-heap on latency, at most kSlowest
  // The identifier of recent requests by frame number (direct-mapped: an
  // answer comes within a few thousand frames, or latency keys by its own).
  struct Pending {
    std::uint64_t n = 0;
    char ident[3] = {};
  };
  std::vector<Pending> pending = std::vector<Pending>(8192);

 private:
  // Counts a finding; the example it became, or nullptr when the code has
  // its examples already.
  Example* finding(std::string_view code, std::optional<ACode> acode, top::Severity sev,
                   std::int64_t ts, const FrameEvent* e, std::uint32_t at,
                   const std::string& message, const std::string* sender);
  void motion(const FrameEvent& e, ConvData& c);
  // Hashed views of the maps' keys (std::map nodes do not move): a finding
  // code's statistics and an identifier's latency bins in one hash lookup,
  // instead of a walk of string comparisons per frame.
  std::unordered_map<std::string_view, CodeStat*> code_at_;
  std::unordered_map<std::string_view, std::array<std::uint64_t, kLatencyBins>*> bins_at_;
  ConvData* last_conv_ = nullptr;
};

// ---- the analysis --------------------------------------------------------

struct AngleResult {
  const AngleCommand* cmd = nullptr;  // in the sink's conversation
  std::uint64_t conv = 0;
  std::string_view attitude;  // the attitude compared with: "GAC", "GIA", "" none
  float start = 0;            // attitude when the command came, deg
  // the target clamped to the model's range, in the attitude's convention
  // (up and right positive: command_sign)
  float effective = 0;
  float expected_s = -1;           // |effective - start| / speed, when a speed was given
  float settling_s = -1;           // -1: never settled
  float overshoot_deg = 0;         // past the target, in the direction of motion
  float overshoot_pct = 0;         // of the step
  float final_error = 0;           // last attitude - target (steady-state error)
  float mirrored_settling_s = -1;  // other_way: settling against -target
  std::uint32_t samples = 0;
  bool no_attitude = false;
  bool never_reached = false;
  bool other_way = false;  // moved away: sign inverted
  bool out_of_range = false;
  bool superseded = false;    // a new command on the axis came before it settled
  bool still_moving = false;  // the capture ended while it was on its way to the target
  // which way the command turns the gimbal cannot be told: the model is
  // unknown and a sign trait of the dialect names the command
  // (top::sign_trait_factor); other_way is then no verdict
  bool ambiguous = false;
};

// Consecutive rate commands on one axis with the same value, each within
// the refresh limit of the one before.
struct RateRun {
  std::uint64_t conv = 0, first_frame = 0;
  std::string ident;
  int axis = 0;
  std::int64_t start = 0, end = 0;  // first command, and the end of the last one's effect
  std::uint64_t commands = 0;
  std::int64_t steps = 0;
  int sign = 1;                // steps to the attitude's convention (command_sign)
  bool ambiguous = false;      // that sign cannot be told (AngleResult::ambiguous)
  double commanded = 0;        // deg/s by the catalog's scale, in that convention
  double scale = 1;            // catalog deg/s per step
  double max_interval_ms = 0;  // longest refresh interval inside the run
  double median_interval_ms = 0;
  double measured = 0;  // deg/s, least squares over the run's samples
  std::size_t samples = 0;
  bool measured_ok = false;
  double per_step = 0;  // measured / (steps x sign): negative when it turned the other way
};

struct RefreshGap {
  std::uint64_t conv = 0, frame = 0;  // the command not refreshed in time
  std::string ident;
  std::int64_t t = 0;
  double gap_ms = 0;  // until the next rate command on the axis (or the end)
};

struct StreamResult {
  std::uint64_t conv = 0;
  StreamStat stat;
  std::int64_t bucket_us = 1'000'000;
  std::vector<float> rate;  // measured Hz per bucket from stat.first
  struct Gap {
    std::int64_t t = 0;
    double ms = 0;
  };
  // the longest intervals over diag::kGapPeriods periods (diag::stream_gap),
  // longest first
  std::vector<Gap> gaps;
  std::uint64_t gap_count = 0;
};

struct Fact {
  int rank = 0;  // higher first
  top::Severity severity{};
  std::string text, anchor;
  // The diagnosis it is (top/diagnoses.hpp; its evidence and remedy), with
  // its first frame and the frames that show it; none for the other facts.
  std::optional<top::Diagnosis> code;
  std::uint64_t frame = 0, count = 0;
};

// Which speed unit the rate runs support (SkyDroid): the field's 0.5 deg/s
// per step, the document's 0.1, neither; none when nothing was measured.
enum class ScaleVerdict : std::uint8_t { none, field, document, neither };
// As the JSON's scale_verdict has it: "0.5", "0.1", "neither", "" (none).
std::string_view to_string(ScaleVerdict v) noexcept;

struct Report {
  Options opts;
  const ReportSink* data = nullptr;
  const Stats* stats = nullptr;
  top::Severity worst{};
  top::Model model = top::Model::unknown;
  std::vector<AngleResult> angles;
  std::vector<RateRun> runs;
  std::vector<RefreshGap> gaps;
  std::int64_t refresh_limit_ms = 0;  // the speed-refresh trait (0: none for the model)
  std::string refresh_evidence;
  ScaleVerdict scale_verdict = ScaleVerdict::none;
  double scale_measured = 0;  // median deg/s per step
  std::size_t scale_runs = 0;
  std::size_t scale_other_way = 0;  // SkyDroid runs that turned the other way: not counted
  std::vector<StreamResult> streams;
  std::vector<Fact> facts;
};

Report analyze(const ReportSink& data, const Stats& stats, top::Severity worst, top::Model model,
               const Options& opts);

// The dialect of a conversation: the statistics', else the one its frames
// were decoded with (a conversation on an unknown port).
top::Dialect dialect_of(const Report& r, const ConvStats& c);

// The model of a conversation: the one given, else guessed where the dialect
// leaves one (Topotek: sip) or the commands the device sent leave fewer
// than the dialect's models, with how it was decided; "" when unknown.
std::string model_text(top::Model given, top::Dialect d, const ConvData* c);
std::string model_text(const Report& r, const ConvStats& c);

// The report as JSON (2-space indent) appended to `out`.
void write_json(std::string& out, const Report& r);
// The report as one self-contained HTML page appended to `out`.
void write_html(std::string& out, const Report& r);

// "12:04:10.250" (UTC time of day; the date is in the overview).
std::string clock_text(std::int64_t ts);

}  // namespace topdump::report
