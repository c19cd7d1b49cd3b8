// The text outputs: one line per frame, garbage run and finding, and the
// -V field tree under each frame.
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>

#include "capture/sources.hpp"
#include "output/escape.hpp"
#include "output/output.hpp"

namespace topdump {

void Out::write(const char* p, std::size_t n) {
  if (n && std::fwrite(p, 1, n, f_) != n) failed_ = true;
}

void Out::gather(const char* p, std::size_t n) {
  if (n == 0) return;
  if (!runs_.empty() && runs_.back().first + runs_.back().second == p)
    runs_.back().second += n;
  else
    runs_.emplace_back(p, n);
}

// The runs go out with writev on the stream's descriptor, after what stdio
// holds for it; a stream with no descriptor, or a failed writev, takes the
// rest through fwrite (which then sets the stream's error flag and errno).
void Out::write_gathered() {
  const int fd = std::fflush(f_) == 0 ? fileno(f_) : -1;
  std::size_t i = 0;
  if (fd >= 0) {
    std::vector<iovec> iov;
    iov.reserve(std::min<std::size_t>(runs_.size(), IOV_MAX));
    while (i < runs_.size()) {
      iov.clear();
      for (std::size_t j = i; j < runs_.size() && iov.size() < IOV_MAX; ++j)
        iov.push_back({const_cast<char*>(runs_[j].first), runs_[j].second});
      const ssize_t w = ::writev(fd, iov.data(), static_cast<int>(iov.size()));
      if (w < 0) {
        if (errno == EINTR) continue;
        break;
      }
      // skip what was written, splitting a run written in part
      auto left = static_cast<std::size_t>(w);
      while (left > 0 && left >= runs_[i].second) left -= runs_[i++].second;
      if (left > 0) {
        runs_[i].first += left;
        runs_[i].second -= left;
      }
    }
  }
  for (; i < runs_.size(); ++i) write(runs_[i].first, runs_[i].second);
  runs_.clear();
}

void Out::flush() {
  if (window_ > 0) {
    release(true);
  } else {
    write(buf_.data(), buf_.size());
    buf_.clear();
  }
  if (std::fflush(f_) != 0 || std::ferror(f_)) failed_ = true;
}

void Out::hold(std::int64_t ts, std::uint64_t record, bool first) {
  const std::size_t len = buf_.size() - mark_;
  bool resort = false;
  if (ts != kNoTime && pending_ > 0) {
    for (std::size_t i = head_; i < spans_.size(); ++i)
      if (Span& x = spans_[i]; x.pending && x.record < record) {
        x.key = ts;
        x.pending = false;
        --pending_;
        resort = true;
      }
  }
  const std::int64_t key = first ? INT64_MIN : ts == kNoTime ? INT64_MAX : ts;
  const Span span{key, record, cur_, mark_, len, !first && ts == kNoTime};
  if (spans_.size() == head_ || spans_.back().key <= key) {
    spans_.push_back(span);
  } else {  // a late event: after the held ones of the same time or earlier
    auto at = std::upper_bound(spans_.begin() + static_cast<std::ptrdiff_t>(head_), spans_.end(),
                               key, [](std::int64_t k, const Span& x) { return k < x.key; });
    spans_.insert(at, span);
  }
  if (resort)
    std::stable_sort(spans_.begin() + static_cast<std::ptrdiff_t>(head_), spans_.end(),
                     [](const Span& x, const Span& y) { return x.key < y.key; });
  if (span.pending) ++pending_;
  ++chunks_[cur_].live;
  held_ += len;
  since_ += len;
  mark_ = buf_.size();
  if (ts != kNoTime && (newest_ == kNoTime || ts > newest_)) newest_ = ts;
  if (since_ >= kChunk || spans_.size() - head_ > kMaxHeldEvents) release(false);
  if (buf_.size() >= kChunk) next_chunk();
}

// buf_ (chunk cur_, which holds events still to be written) is kept as that
// chunk's bytes; appends go on in a free chunk's buffer.
void Out::next_chunk() {
  std::size_t next;
  if (!free_.empty()) {
    next = free_.back();
    free_.pop_back();
  } else {
    next = chunks_.size();
    chunks_.emplace_back();
  }
  chunks_[cur_].bytes.swap(buf_);
  buf_.swap(chunks_[next].bytes);
  buf_.clear();
  cur_ = next;
  mark_ = 0;
}

void Out::release(bool all) {
  since_ = 0;
  const std::size_t n = spans_.size();
  std::size_t k = all ? n : head_;
  if (!all) {
    const std::int64_t horizon = newest_ == kNoTime ? INT64_MIN : newest_ - window_;
    while (k < n && spans_[k].key <= horizon) ++k;
    // over the limits: the oldest go out whatever their time, down to 7/8
    std::size_t held = held_;
    for (std::size_t i = head_; i < k; ++i) held -= spans_[i].len;
    while (k < n && (n - k > kMaxHeldEvents - kMaxHeldEvents / 8 ||
                     (held > kMaxHeldBytes - kMaxHeldBytes / 8 && held > spans_[k].len))) {
      held -= spans_[k].len;
      ++k;
    }
  }
  for (std::size_t i = head_; i < k; ++i) gather(bytes_of(spans_[i]), spans_[i].len);
  write_gathered();
  for (std::size_t j = head_; j < k; ++j) {
    const Span& x = spans_[j];
    if (x.pending) --pending_;
    held_ -= x.len;
    if (--chunks_[x.chunk].live == 0) {
      if (x.chunk == cur_) {  // every event appended to it is written
        buf_.clear();
        mark_ = 0;
      } else {
        chunks_[x.chunk].bytes.clear();
        free_.push_back(x.chunk);
      }
    }
  }
  head_ = k;
  if (head_ == n) {
    spans_.clear();
    head_ = 0;
  } else if (head_ >= 4096 && head_ * 2 > n) {
    spans_.erase(spans_.begin(), spans_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
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
  if (e.copy_of) s += " | copy of #" + std::to_string(e.copy_of);
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
  out_.done(e.ts, e.pos.record);
}
void TextSink::garbage(const GarbageEvent& e) {
  out_.buf() += garbage_line(e) + "\n";
  out_.done(e.ts, e.pos.record);
}
void TextSink::note(const NoteEvent& e) {
  out_.buf() += note_line(e) + "\n";
  out_.done(e.ts, e.pos.record);
}

void SummarySink::frame(const FrameEvent& e) {
  ++frames_;
  at(e.ts);
  for (const top::Finding* x : all_findings(*e.entry->frame, e.entry->decoded)) count(x->severity);
  for (const Note& n : e.notes) count(n.severity);
  inner_.frame(e);
}
void SummarySink::garbage(const GarbageEvent& e) {
  ++garbage_;
  at(e.ts);
  count(e.item->finding.severity);
  inner_.garbage(e);
}
void SummarySink::note(const NoteEvent& e) {
  at(e.ts);
  count(e.note.severity);
  if (e.note.code == ACode::unanswered) ++unanswered_;
  inner_.note(e);
}

std::string SummarySink::text() const {
  auto n = [](std::uint64_t v, const char* one, const char* many) {
    return std::to_string(v) + " " + (v == 1 ? one : many);
  };
  std::string s = "-- summary: " + n(frames_, "frame", "frames") + ", " +
                  n(errors_, "error", "errors") + ", " + n(warnings_, "warning", "warnings") +
                  ", " + std::to_string(unanswered_) + " unanswered, " + std::to_string(garbage_) +
                  " garbage";
  if (first_ != kNoTime) {
    char b[48];
    std::snprintf(b, sizeof b, " (%.3f s)", static_cast<double>(last_ - first_) / 1e6);
    s += ", " + format_time(first_) + " to " + format_time(last_) + b;
  } else {
    s += ", no timestamps";
  }
  return s;
}

}  // namespace topdump
