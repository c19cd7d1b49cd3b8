// The session layer of topdump: sources hand it timestamped chunks with
// endpoints; it runs one top::StreamDecoder per conversation and direction,
// decodes each frame for the conversation's dialect, pairs requests with
// responses, watches streams, keeps the statistics and hands each event to a
// Sink. Memory is bounded: conversations, pending requests, TCP held bytes
// and the decode cache all have named limits.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "capture/sink.hpp"
#include "findings/afindings.hpp"
#include "session/events.hpp"
#include "session/filter.hpp"
#include "session/pairing.hpp"
#include "session/stats.hpp"
#include "session/tcp_reassembly.hpp"
#include "top/top.hpp"

namespace topdump {

// Named limits (findings fire when they are hit); kMaxPending and the TCP
// limits are in session/pairing.hpp and session/tcp_reassembly.hpp.
inline constexpr std::size_t kMaxConversations = 4096;

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

class Analyzer final : public CaptureSink {
 public:
  Analyzer(AnalyzerOptions opts, Sink& sink);
  ~Analyzer();
  Analyzer(const Analyzer&) = delete;
  Analyzer& operator=(const Analyzer&) = delete;

  void set_filter(Filter f) {
    filter_ = std::move(f);
    filtering_ = filter_.active();
  }
  // done() (CaptureSink): -c reached: the selected frames are all there;
  // the rest of the input is skipped (callers may stop reading).

  // A record was read (counts records; call once per packet/line/chunk).
  void record(bool top_traffic) override;
  // A UDP payload: decoded on its own (frames never span datagrams).
  void datagram(std::int64_t ts, const Endpoint& src, const Endpoint& dst, std::string_view payload,
                std::uint64_t record, std::uint32_t offset) override;
  // A TCP segment: reassembled per direction (SYN, retransmission, overlap,
  // out of order, gaps) before decoding.
  void segment(std::int64_t ts, const Endpoint& src, const Endpoint& dst, std::uint32_t seq,
               bool syn, std::string_view payload, std::uint64_t record,
               std::uint32_t offset) override;
  // Bytes of an in-order byte stream (serial line, one direction).
  void chunk(std::int64_t ts, Transport t, const Endpoint& src, const Endpoint& dst,
             std::string_view bytes, std::uint64_t record, std::uint64_t offset) override;
  // Releases frames held to see whether CR/LF follows (live serial).
  void flush_streams() override;
  // The serial recording holds both directions (socat, a merge of two taps).
  void both_ways() override { both_ways_ = true; }
  // A source finding (truncated file, bad packet, bad log line).
  void source_note(std::int64_t ts, ACode code, std::string message, std::uint64_t record,
                   std::uint64_t offset) override;
  // End of input: flushes decoders, expires pending requests, checks streams.
  void finish();

  // The statistics so far (per-identifier, per-code and latency tables are
  // folded in from fast counters on each call).
  const Stats& stats() const;
  // The worst severity of any finding seen (for the exit status).
  top::Severity worst() const noexcept { return worst_; }
  // A warning or error diagnosis (top/diagnoses.hpp) was reported: the exit
  // status is 1, as for an error finding.
  bool diagnosed() const noexcept { return diagnosed_; }
  std::uint64_t frames_seen() const noexcept { return frame_no_; }
  // After finish(): no-frames (`what`: the input, "no TOP frame found")
  // when no frame was seen, unless a diagnosis already named why (a serial
  // line read at the wrong speed, baud-mismatch): one cause, one item.
  void note_if_no_frames(std::string what);

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
  bool both_ways_ = false;  // the serial inputs record both directions (both_ways())
  mutable Stats stats_;
  top::Severity worst_ = top::Severity::info;
  bool diagnosed_ = false;
  std::uint64_t frame_no_ = 0;
  std::uint64_t selected_ = 0;  // frames the filter selected
  bool started_ = false;        // the first timestamp seen (relative filter times)
  friend struct Impl;
};

}  // namespace topdump
