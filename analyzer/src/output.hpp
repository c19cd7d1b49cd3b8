// topdump outputs: one line per frame, the -V field tree, JSON Lines (a fast
// writer proven equal to the nlohmann reference by tests), CSV, and the
// statistics as text or JSON. Schema: docs/topdump-json.md.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "analyzer.hpp"
#include "render.hpp"

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

// Reference JSON of each event, built with nlohmann.
json frame_event_json(const FrameEvent& e);
json garbage_event_json(const GarbageEvent& e);
json note_event_json(const NoteEvent& e);
// The keys of frame_json(), written without nlohmann (no braces).
void write_frame_body(std::string& out, const top::Frame& f, const top::Decoded& d);
// The fast writer of a frame event: appends one line (with '\n').
void write_frame_json(std::string& out, const FrameEvent& e);
// note_event_json(e).dump() plus a newline, written directly.
void write_note_json(std::string& out, const NoteEvent& e);

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
  CsvSink(Out& out, std::vector<std::string> columns);
  void frame(const FrameEvent& e) override;

 private:
  Out& out_;
  std::vector<std::string> cols_;
};

// Forwards to a sink and prints source findings to stderr with the file name.
json stats_json(const Stats& s, top::Severity worst);
std::string stats_text(const Stats& s, top::Severity worst);

}  // namespace topdump
