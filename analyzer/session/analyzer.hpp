// The session layer of topdump: sources hand it timestamped chunks with
// endpoints; it runs one top::StreamDecoder per conversation and direction,
// decodes each frame for the conversation's dialect, pairs requests with
// responses, watches streams, keeps the statistics and hands each event to a
// Sink. Memory is bounded: conversations, pending requests, TCP held bytes
// and the decode cache all have named limits.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "findings/afindings.hpp"
#include "pcapio/endpoint.hpp"
#include "top/top.hpp"

namespace topdump {

// Named limits (findings fire when they are hit).
inline constexpr std::size_t kMaxConversations = 4096;
inline constexpr std::size_t kMaxPending = 256;       // per conversation
inline constexpr std::size_t kMaxTcpHeld = 1u << 20;  // out-of-order bytes per direction
inline constexpr std::size_t kMaxTcpSegments = 1024;  // out-of-order segments per direction
inline constexpr std::size_t kMaxStatsConversations = 4096;

inline constexpr std::int64_t kNoTime = INT64_MIN;

enum class Transport : std::uint8_t { udp, tcp, serial };
std::string_view to_string(Transport t) noexcept;

// One end of a conversation: an IP address and port, or a name (serial).
using Endpoint = pcapio::Endpoint;

// Where a frame sits in the capture.
struct Position {
  std::uint64_t record = 0;  // 1-based record (packet, log chunk, line, CSV row)
  std::uint32_t index = 0;   // 0-based index among the items of the record
  std::uint64_t offset = 0;  // byte offset of the first byte in the record
};

struct Conversation;

// A finding of the session or source layer.
struct Note {
  ACode code{};
  top::Severity severity{};
  std::string message;
  std::uint64_t frame = 0;  // the frame it is about (0: none)
  // The identifier and TOP addresses of what it is about (a request, a
  // stream), for the filter; zero when it is about no frame (TCP, files).
  char ident[3] = {};
  char src = 0, dst = 0;
};

// A decoded frame with its findings summarised.
struct DecodedEntry {
  const top::Frame* frame = nullptr;  // the parser's, valid during the event
  top::Decoded decoded;
  top::Severity worst = top::Severity::info;
  bool bad_checksum = false;
};

struct FrameEvent {
  std::uint64_t n = 0;        // 1-based frame number
  std::int64_t ts = kNoTime;  // microseconds since the epoch
  Position pos;
  std::uint64_t stream_offset = 0;  // TCP/serial: offset in the direction's byte stream
  Transport transport{};
  const Conversation* conv = nullptr;
  const std::string* from = nullptr;  // endpoint text
  const std::string* to = nullptr;
  const DecodedEntry* entry = nullptr;
  std::uint64_t reply_to = 0;  // frame number of the request answered
  std::int64_t latency_us = -1;
  std::vector<Note> notes;  // session findings on this frame
  top::Severity worst() const noexcept;
  std::uint64_t conv_id() const noexcept;
};

struct GarbageEvent {
  std::int64_t ts = kNoTime;
  Position pos;
  Transport transport{};
  const Conversation* conv = nullptr;
  const std::string* from = nullptr;
  const std::string* to = nullptr;
  const top::StreamItem* item = nullptr;
  std::uint64_t conv_id() const noexcept;
};

struct NoteEvent {
  std::int64_t ts = kNoTime;
  Position pos;
  Transport transport{};
  const Conversation* conv = nullptr;  // may be null (file-level)
  const std::string* from = nullptr;
  const std::string* to = nullptr;
  Note note;
  std::uint64_t conv_id() const noexcept;
};

class Sink {
 public:
  virtual ~Sink() = default;
  virtual void frame(const FrameEvent&) {}
  virtual void garbage(const GarbageEvent&) {}
  virtual void note(const NoteEvent&) {}
};

// Latency: exact min/max/count; exact nearest-rank quantiles up to 4096
// samples, then from a log histogram (within 1%), so memory stays bounded.
class Latency {
 public:
  void add(std::int64_t us);
  std::uint64_t count() const noexcept { return count_; }
  std::int64_t min() const noexcept { return min_; }
  std::int64_t max() const noexcept { return max_; }
  std::int64_t quantile(double q) const;  // microseconds
  // The 1% log bucket of a latency, and the same by its formula (tests).
  static std::size_t bucket(std::int64_t us);
  static std::size_t bucket_exact(std::int64_t us);

 private:
  static std::int64_t bucket_value(std::size_t b);
  static constexpr std::size_t kExact = 4096;  // exact quantiles up to this many samples
  std::vector<std::uint32_t> buckets_;
  std::vector<std::int64_t> exact_;
  std::uint64_t count_ = 0;
  std::int64_t min_ = 0, max_ = 0;
};

struct StreamStat {
  std::string ident;         // GAC, GIC (device pushes) or FAI (client stream)
  double asked_hz = 0;       // 0: enable without a rate (Topotek)
  std::string asked_by;      // the request that switched it on: GAA, GIA, FAE
  bool from_client = false;  // the client sends it (FAI): never a request to answer
  std::uint64_t frames = 0;
  std::int64_t first = kNoTime, last = kNoTime;
  double measured_hz() const;
};

struct ConvStats {
  std::uint64_t id = 0;
  std::string a, b;  // endpoint texts, a is the first sender
  Transport transport{};
  top::Dialect dialect = top::Dialect::unknown;
  std::uint64_t frames = 0, requests = 0, responses = 0, paired = 0;
  std::vector<StreamStat> streams;
};

struct Stats {
  std::uint64_t records = 0;          // packets, log chunks, lines
  std::uint64_t records_skipped = 0;  // not TOP traffic
  std::uint64_t frames = 0;
  std::uint64_t bad_checksum = 0;
  std::uint64_t garbage = 0;  // garbage runs
  std::uint64_t error_frames = 0;
  std::uint64_t requests = 0, responses = 0, paired = 0, unanswered = 0, unsolicited = 0;
  std::map<std::string, std::uint64_t> per_ident;
  std::map<std::string, std::uint64_t> per_code;  // frame, catalog and analyzer codes
  std::map<std::string, Latency> latency;         // per identifier
  std::vector<ConvStats> conversations;
  std::uint64_t conversations_dropped = 0;
  std::int64_t first = kNoTime, last = kNoTime;
};

struct AnalyzerOptions {
  top::Dialect dialect = top::Dialect::unknown;  // forced when not unknown
  top::Model model = top::Model::unknown;
  std::int64_t timeout_us = 2'000'000;  // unanswered after this
  std::int64_t repeat_window_us = 100'000;
  std::size_t max_conversations = kMaxConversations;
  std::size_t max_tcp_held = kMaxTcpHeld;
  bool stats = true;  // count frames in stats
  // false: frames are judged and counted but not described: no decoded field
  // values, and empty messages in catalog findings and session notes (for a
  // sink that shows neither: topdump stats). Source notes keep theirs.
  bool detail = true;
};

// The command line's selection. It applies to everything reported alike:
// frames, garbage, findings (session notes about a request or stream), the
// statistics and the exit status; pairing and timeouts still see every
// frame. Findings about the capture file itself (no conversation) are kept
// whatever the identifier, address and time selection.
struct Filter {
  std::vector<std::string> idents;  // empty: all (matched case-insensitively)
  std::vector<std::string> addrs;   // TOP address letters or network hosts
  top::Severity min_severity = top::Severity::info;
  bool severity_set = false;
  std::int64_t from = kNoTime, to = kNoTime;
  // --from +1.5s: microseconds after the first timestamp of the input,
  // resolved into from/to when the analyzer sees it.
  std::int64_t from_rel = kNoTime, to_rel = kNoTime;
  // --finding: only frames and events that carry one of these codes.
  std::vector<top::FindingCode> findings;
  std::vector<ACode> afindings;
  // --mute: these findings are dropped wherever they appear (not shown, not
  // counted, not in the exit status).
  std::vector<top::FindingCode> mute;
  std::vector<ACode> amute;
  // -c: the input ends after this many selected frames (0: no limit).
  std::uint64_t max_frames = 0;

  bool selects(const FrameEvent& e) const;
  bool selects(const NoteEvent& e) const;
  bool selects(const GarbageEvent& e) const;
  bool selects_time(std::int64_t ts) const;
  bool selects_ident(std::string_view ident) const;
  bool mutes(top::FindingCode c) const {
    return !mute.empty() && std::find(mute.begin(), mute.end(), c) != mute.end();
  }
  bool mutes(ACode c) const {
    return !amute.empty() && std::find(amute.begin(), amute.end(), c) != amute.end();
  }
  bool active() const;
  // Resolves relative times against the input's first timestamp.
  void start_at(std::int64_t first);
  // Parses a code for --finding/--mute (a frame, catalog or analyzer code);
  // false when there is none of that name.
  bool add_code(std::string_view name, bool muted);
};

// "1.5", "1.5s", "200ms", "250us": a duration in microseconds (relative
// --from/--to); nullopt when it is none of these or negative.
std::optional<std::int64_t> parse_duration(std::string_view s);

class Analyzer {
 public:
  Analyzer(AnalyzerOptions opts, Sink& sink);
  ~Analyzer();
  Analyzer(const Analyzer&) = delete;
  Analyzer& operator=(const Analyzer&) = delete;

  void set_filter(Filter f) {
    filter_ = std::move(f);
    filtering_ = filter_.active();
  }
  // -c reached: the selected frames are all there; the rest of the input
  // is skipped (callers may stop reading).
  bool done() const noexcept { return done_; }
  // A record was read (counts records; call once per packet/line/chunk).
  void record(bool top_traffic);
  // A UDP payload: decoded on its own (frames never span datagrams).
  void datagram(std::int64_t ts, const Endpoint& src, const Endpoint& dst, std::string_view payload,
                std::uint64_t record, std::uint32_t offset);
  // A TCP segment: reassembled per direction (SYN, retransmission, overlap,
  // out of order, gaps) before decoding.
  void segment(std::int64_t ts, const Endpoint& src, const Endpoint& dst, std::uint32_t seq,
               bool syn, std::string_view payload, std::uint64_t record, std::uint32_t offset);
  // Bytes of an in-order byte stream (serial line, one direction).
  void chunk(std::int64_t ts, Transport t, const Endpoint& src, const Endpoint& dst,
             std::string_view bytes, std::uint64_t record, std::uint64_t offset);
  // Releases frames held to see whether CR/LF follows (live serial).
  void flush_streams();
  // A source finding (truncated file, bad packet, bad log line).
  void source_note(std::int64_t ts, ACode code, std::string message, std::uint64_t record,
                   std::uint64_t offset);
  // End of input: flushes decoders, expires pending requests, checks streams.
  void finish();

  // The statistics so far (per-identifier, per-code and latency tables are
  // folded in from fast counters on each call).
  const Stats& stats() const;
  // The worst severity of any finding seen (for the exit status).
  top::Severity worst() const noexcept { return worst_; }
  std::uint64_t frames_seen() const noexcept { return frame_no_; }

 private:
  // With a filter: false once -c is reached (the record is skipped); the
  // first timestamp resolves relative times.
  bool take(std::int64_t ts) {
    if (done_) return false;
    if (!started_ && ts != kNoTime) {
      started_ = true;
      filter_.start_at(ts);
    }
    return true;
  }
  struct Impl;
  std::unique_ptr<Impl> impl_;
  AnalyzerOptions opts_;
  Sink& sink_;
  Filter filter_;
  bool filtering_ = false;  // filter_.active(), asked once per frame
  mutable Stats stats_;
  top::Severity worst_ = top::Severity::info;
  std::uint64_t frame_no_ = 0;
  std::uint64_t selected_ = 0;  // frames the filter selected
  bool done_ = false;
  bool started_ = false;  // the first timestamp seen (relative filter times)
  friend struct Impl;
};

}  // namespace topdump

namespace topdump {
// True when a payload on an unknown port carries something that starts like
// a TOP frame ("#tp", "#TP", "#tP", "#Tp", "#PDP16TMP").
bool looks_like_top(std::string_view payload) noexcept;
}  // namespace topdump
