// topdump outputs: one line per frame and the -V field tree (text_out.cpp),
// JSON Lines (json_events.cpp, through the one JSON writer of
// json_writer.hpp; schema: docs/topdump-json.md), CSV (csv_out.cpp), and
// the statistics as text or JSON (stats_out.cpp).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "analyzer.hpp"
#include "render.hpp"
#include "sources.hpp"

namespace topdump {

// Buffered stdout (or any FILE*); flushes every event when `live`.
class Out {
 public:
  explicit Out(std::FILE* f, bool live = false) : f_(f), live_(live) { buf_.reserve(1 << 17); }
  ~Out() { flush(); }
  std::string& buf() { return buf_; }
  void done() {
    if (live_ || buf_.size() >= (1u << 16)) flush();
  }
  void flush();

 private:
  std::FILE* f_;
  bool live_;
  std::string buf_;
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

// The CSV columns topdump knows; "field.NAME" selects a decoded field.
const std::vector<std::string>& csv_columns();
bool csv_column_ok(const std::string& c);

class CsvSink : public Sink {
 public:
  CsvSink(Out& out, const std::vector<std::string>& columns);
  void frame(const FrameEvent& e) override;

 private:
  Out& out_;
  std::vector<int> cols_;            // index into the column table, -1: a field
  std::vector<std::string> fields_;  // the field's name where cols_ is -1
};

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
