// The statistics of a capture: counts, latency per identifier, streams and
// conversations.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "capture/sink.hpp"
#include "diagnoses/stream_never_started.hpp"
#include "diagnoses/stream_rate.hpp"
#include "diagnoses/stream_stalled.hpp"
#include "top/top.hpp"

namespace topdump {

inline constexpr std::size_t kMaxStatsConversations = 4096;

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
  void count_in_bucket(std::int64_t us);
  // Filled once there are more than kExact samples: a histogram of 1%
  // buckets is KBs of zeroes for each identifier paired, which the fuzz
  // targets paid per input (docs/perf/fuzz-speed.md, "Issue 48: the
  // per-conversation cost").
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
  bool enabled = true;       // no switch turned it off since it was asked for
  // Pushed at a rate while on (top::StreamSpec::periodic: an attitude
  // push); false for an event push (the field's Topotek OFT, ODR, ODZ),
  // which no stream judge (stalled, rate, never started) judges.
  bool periodic = true;
  std::uint64_t frames = 0;
  std::int64_t first = kNoTime, last = kNoTime;
  // The stream's diagnoses as it streams by (analyzer/diagnoses/).
  diag::StallWatch stall;
  diag::NeverStartedWatch never;
  double measured_hz() const;
  // Asked a rate, measured one, and more than top::stream_rate_tolerance
  // off it (diag::off_rate: the rule of the stream-rate diagnosis).
  bool off_rate() const;
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
  std::uint64_t copies = 0;  // the device's copies of its own frames (FrameEvent::copy_of)
  std::map<std::string, std::uint64_t> per_ident;
  std::map<std::string, std::uint64_t> per_code;  // frame, catalog and analyzer codes
  std::map<std::string, Latency> latency;         // per identifier
  std::vector<ConvStats> conversations;
  std::uint64_t conversations_dropped = 0;
  std::int64_t first = kNoTime, last = kNoTime;
};

}  // namespace topdump
