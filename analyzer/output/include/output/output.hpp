// topdump outputs: one line per frame and the -V field tree (text_out.cpp),
// JSON Lines (json_events.cpp, through the one JSON writer of
// json_writer.hpp; schema: docs/topdump-json.md), CSV (csv_out.cpp), and
// the statistics as text or JSON (stats_out.cpp).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "capture/sources.hpp"
#include "output/render.hpp"
#include "session/analyzer.hpp"

namespace topdump {

// Buffered stdout (or any FILE*) for the events of a sink, each finished by
// done(). `live`: every event is written at once. With a reorder window
// (read), events are held and written in capture-time order: an event is
// written once capture time has moved `window_us` past it (or when more
// than kMaxHeldEvents / kMaxHeldBytes are held, the oldest first, or at
// flush()). An event with no time (a log line without one) goes before the
// first timed event of a later record, or at the end. An event that arrives
// later than the window reaches is written ahead of those still held.
// A failed write sets failed() (and stdout's error flag).
class Out {
 public:
  static constexpr std::size_t kMaxHeldEvents = 1u << 17;
  static constexpr std::size_t kMaxHeldBytes = 64u << 20;
  explicit Out(std::FILE* f, bool live = false, std::int64_t window_us = 0)
      : f_(f), live_(live), window_(live ? 0 : window_us) {
    buf_.reserve(1 << 17);
  }
  ~Out() { flush(); }
  Out(const Out&) = delete;
  Out& operator=(const Out&) = delete;
  std::string& buf() { return buf_; }
  // The bytes appended since the last done() are one event at `ts` of
  // capture record `record`.
  void done(std::int64_t ts = kNoTime, std::uint64_t record = 0) {
    if (window_ > 0) return hold(ts, record, false);
    if (live_ || buf_.size() >= (1u << 16)) flush();
  }
  // The bytes appended so far come before every event (a CSV header).
  void head() {
    if (window_ > 0) hold(kNoTime, 0, true);
  }
  void flush();
  bool failed() const noexcept { return failed_; }

 private:
  struct Span {
    std::int64_t key;  // the time; INT64_MAX while an untimed event waits for one
    std::uint64_t record;
    std::size_t chunk, begin, len;
    bool pending;
  };
  // window_ > 0: held bytes sit in chunks of about kChunk bytes, buf_ being
  // the one events are appended to (chunk cur_); a chunk is reused once
  // every event in it is written, so what is held and written stays in the
  // cache and nothing is moved.
  static constexpr std::size_t kChunk = 1u << 16;
  struct Chunk {
    std::string bytes;  // empty for cur_ (its bytes are buf_)
    std::size_t live = 0;
  };
  void hold(std::int64_t ts, std::uint64_t record, bool first);
  void release(bool all);
  void next_chunk();
  const char* bytes_of(const Span& x) const {
    return (x.chunk == cur_ ? buf_ : chunks_[x.chunk].bytes).data() + x.begin;
  }
  void write(const char* p, std::size_t n);
  // Runs of held bytes leave through one gathered write (writev) per
  // release, straight from the chunks: no copy into stdio's buffer.
  void gather(const char* p, std::size_t n);
  void write_gathered();
  std::FILE* f_;
  bool live_;
  std::int64_t window_;
  bool failed_ = false;
  std::string buf_;
  std::vector<Chunk> chunks_ = std::vector<Chunk>(1);
  std::vector<std::size_t> free_;  // chunks to reuse
  std::size_t cur_ = 0;
  std::vector<Span> spans_;  // sorted by key from head_ on (stable)
  std::size_t head_ = 0;     // spans_ before it were written
  std::size_t mark_ = 0, held_ = 0, pending_ = 0, since_ = 0;
  std::int64_t newest_ = kNoTime;
  std::vector<std::pair<const char*, std::size_t>> runs_;
};

// Each event of read --json as one line (with '\n') appended to `out`.
void write_frame_json(std::string& out, const FrameEvent& e);
void write_garbage_json(std::string& out, const GarbageEvent& e);
void write_note_json(std::string& out, const NoteEvent& e);
// A frame and a run of garbage of topdump frame --json (one line each):
// the argument they came from (1-based), their byte offset in it, then the
// keys of a frame event's frame, or "garbage", "length", "preview",
// "findings" and "ok".
void write_frame_json(std::string& out, std::size_t arg, std::size_t offset, const top::Frame& f,
                      const top::Decoded& d);
void write_garbage_json(std::string& out, std::size_t arg, const top::StreamItem& g);

// "2 udp 10.0.0.1:40000 > 10.0.0.2:5000 ..." (no newline)
std::string frame_line(const FrameEvent& e);
std::string garbage_line(const GarbageEvent& e);
std::string note_line(const NoteEvent& e);

class TextSink : public Sink {
 public:
  TextSink(Out& out, bool verbose) : out_(out), verbose_(verbose) {}
  void frame(const FrameEvent& e) override;
  void garbage(const GarbageEvent& e) override;
  void note(const NoteEvent& e) override;

 private:
  Out& out_;
  bool verbose_;
};

class JsonSink : public Sink {
 public:
  explicit JsonSink(Out& out) : out_(out) {}
  void frame(const FrameEvent& e) override;
  void garbage(const GarbageEvent& e) override;
  void note(const NoteEvent& e) override;

 private:
  Out& out_;
};

// Passes every event on to `inner` and counts what it saw, for the line
// read prints at its end on a terminal (as live prints its statistics):
// "-- summary: 33 frames, 1 error, 15 warnings, 2 unanswered, 0 garbage,
// 2024-05-01T12:00:00.000000Z to 2024-05-01T12:00:01.200000Z (1.200 s)".
// Errors and warnings count findings (frame, catalog, session and source).
class SummarySink : public Sink {
 public:
  explicit SummarySink(Sink& inner) : inner_(inner) {}
  void frame(const FrameEvent& e) override;
  void garbage(const GarbageEvent& e) override;
  void note(const NoteEvent& e) override;
  std::string text() const;

 private:
  void count(top::Severity s) {
    (s == top::Severity::error ? errors_ : s == top::Severity::warning ? warnings_ : infos_)++;
  }
  void at(std::int64_t ts) {
    if (ts == kNoTime) return;
    if (first_ == kNoTime || ts < first_) first_ = ts;
    if (last_ == kNoTime || ts > last_) last_ = ts;
  }
  Sink& inner_;
  std::uint64_t frames_ = 0, garbage_ = 0, errors_ = 0, warnings_ = 0, infos_ = 0, unanswered_ = 0;
  std::int64_t first_ = kNoTime, last_ = kNoTime;
};

// The CSV columns topdump knows, in their order (docs/topdump-csv.md), and
// the JSON key names also accepted for some ("command=title").
const std::vector<std::string>& csv_columns();
std::vector<std::string> csv_aliases();
// Why a --csv column is not one ("" when it is): an unknown column (the
// message lists them) or a field.NAME / field.NAME.unit whose NAME no
// command of the catalog has.
std::string csv_column_error(const std::string& c);

struct CsvRow;

// One row per frame, garbage run and finding (the `type` column tells them
// apart); a cell that does not apply to a row is empty.
class CsvSink : public Sink {
 public:
  CsvSink(Out& out, const std::vector<std::string>& columns);
  void frame(const FrameEvent& e) override;
  void garbage(const GarbageEvent& e) override;
  void note(const NoteEvent& e) override;

 private:
  void row(const CsvRow& r, std::int64_t ts, std::uint64_t record);
  Out& out_;
  std::vector<int> cols_;            // index into the column table, -1: a field
  std::vector<std::string> fields_;  // the field's name where cols_ is -1
  std::vector<bool> units_;          // field.NAME.unit: its unit, not its value
};

// The pairing totals, in the order every writer gives them: their stats
// --json keys ("pairing", where "copies" follows them) and the names stats
// and the report's summary print them with.
struct StatsCount {
  std::string_view name;
  std::uint64_t Stats::*count;
};
inline constexpr StatsCount kPairingCounts[] = {{"requests", &Stats::requests},
                                                {"responses", &Stats::responses},
                                                {"paired", &Stats::paired},
                                                {"unanswered", &Stats::unanswered},
                                                {"unsolicited", &Stats::unsolicited}};

// The statistics as JSON appended to `out`: indented by `indent` spaces per
// level (stats --json: 2), or on one line with indent < 0 and, when `type`
// is given, a leading "type" key (the last line of live and serial --json).
// `inputs`, when given, is written first: what each file was read as.
void write_stats_json(std::string& out, const Stats& s, top::Severity worst, int indent,
                      std::string_view type = {}, const std::vector<InputInfo>* inputs = nullptr);
// {"type":"input","file":..,"format":..,"link":..} and a newline.
void write_input_json(std::string& out, const InputInfo& i);
// "sample.pcap: pcap, link type EN10MB"
std::string input_text(const InputInfo& i);
std::string stats_text(const Stats& s, top::Severity worst);

}  // namespace topdump
