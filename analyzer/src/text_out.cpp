// The text outputs: one line per frame, garbage run and finding, and the
// -V field tree under each frame.
#include <cstdio>

#include "escape.hpp"
#include "output.hpp"
#include "sources.hpp"

namespace topdump {

void Out::flush() {
  if (!buf_.empty()) {
    std::fwrite(buf_.data(), 1, buf_.size(), f_);
    buf_.clear();
  }
  std::fflush(f_);
}

namespace {

std::string severity_tag(const top::Finding& f) {
  return std::string(top::to_string(f.severity)) + " " + std::string(top::to_string(f.code)) + "@" +
         std::to_string(f.offset) + ": " + f.message +
         (f.quirk.empty() ? "" : " [quirk: " + std::string(f.quirk) + "]");
}

std::string where(std::int64_t ts, Transport t, const std::string* from, const std::string* to) {
  std::string s = format_time(ts);
  if (from) s += " " + std::string(to_string(t)) + " " + *from + " > " + *to;
  return s;
}

}  // namespace

std::string frame_line(const FrameEvent& e) {
  const top::Frame& f = *e.entry->frame;
  const top::Decoded& d = e.entry->decoded;
  std::string s = "#" + std::to_string(e.n) + " " + where(e.ts, e.transport, e.from, e.to);
  s += " rec " + std::to_string(e.pos.record) + "." + std::to_string(e.pos.index) + "@" +
       std::to_string(e.pos.offset) + " \"" + escape(f.raw) + "\" ";
  s += escape(f.ident_view());
  if (d.role != top::Role::any) {
    s += ' ';
    s += top::to_string(d.role);
  }
  if (d.command) s += " (" + std::string(d.command->title) + ")";
  std::string sum = d.summary();
  if (!sum.empty()) s += ": " + sum;
  if (e.reply_to) {
    s += " | reply to #" + std::to_string(e.reply_to);
    if (e.latency_us >= 0) {
      char b[48];
      std::snprintf(b, sizeof b, " after %.3f ms", static_cast<double>(e.latency_us) / 1000.0);
      s += b;
    }
  }
  for (const top::Finding* x : all_findings(f, d)) s += " | " + severity_tag(*x);
  for (const Note& n : e.notes)
    s += " | " + std::string(top::to_string(n.severity)) + " " + std::string(to_string(n.code)) +
         ": " + n.message;
  return s;
}

std::string garbage_line(const GarbageEvent& e) {
  const top::StreamItem& g = *e.item;
  return "-- " + where(e.ts, e.transport, e.from, e.to) + " rec " + std::to_string(e.pos.record) +
         "." + std::to_string(e.pos.index) + "@" + std::to_string(e.pos.offset) + " " +
         std::to_string(g.length) + " bytes \"" + escape(g.preview) +
         (g.length > g.preview.size() ? "..." : "") + "\" | " + severity_tag(g.finding);
}

std::string note_line(const NoteEvent& e) {
  std::string s = "!! " + where(e.ts, e.transport, e.from, e.to);
  if (e.pos.record)
    s += " rec " + std::to_string(e.pos.record) + "@" + std::to_string(e.pos.offset);
  s += " " + std::string(top::to_string(e.note.severity)) + " " +
       std::string(to_string(e.note.code)) + ": " + e.note.message;
  return s;
}

void TextSink::frame(const FrameEvent& e) {
  std::string& o = out_.buf();
  o += frame_line(e);
  o += '\n';
  if (verbose_) {
    o += frame_tree(*e.entry->frame, e.entry->decoded);
    for (const Note& n : e.notes)
      o += "  " + std::string(top::to_string(n.severity)) + " " + std::string(to_string(n.code)) +
           ": " + n.message + "\n";
  }
  out_.done();
}
void TextSink::garbage(const GarbageEvent& e) {
  out_.buf() += garbage_line(e) + "\n";
  out_.done();
}
void TextSink::note(const NoteEvent& e) {
  out_.buf() += note_line(e) + "\n";
  out_.done();
}

}  // namespace topdump
