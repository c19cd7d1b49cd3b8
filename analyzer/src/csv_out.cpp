// read --csv: one row per frame, the columns chosen from one table.
#include <algorithm>
#include <cstdio>

#include "escape.hpp"
#include "output.hpp"
#include "sources.hpp"

namespace topdump {

namespace {

using Cell = std::string (*)(const FrameEvent&);

const top::Frame& frame_of(const FrameEvent& e) { return *e.entry->frame; }
const top::Decoded& decoded_of(const FrameEvent& e) { return e.entry->decoded; }
std::string char_cell(char c) { return escape(std::string_view(&c, 1)); }

struct Column {
  std::string_view name;
  Cell cell;
};

// Every column, in the order --csv lists them.
const Column kColumns[] = {
    {"n", [](const FrameEvent& e) { return std::to_string(e.n); }},
    {"time", [](const FrameEvent& e) { return format_time(e.ts); }},
    {"transport", [](const FrameEvent& e) { return std::string(to_string(e.transport)); }},
    {"from", [](const FrameEvent& e) { return *e.from; }},
    {"to", [](const FrameEvent& e) { return *e.to; }},
    {"conversation", [](const FrameEvent& e) { return std::to_string(e.conv_id()); }},
    {"record", [](const FrameEvent& e) { return std::to_string(e.pos.record); }},
    {"index", [](const FrameEvent& e) { return std::to_string(e.pos.index); }},
    {"offset", [](const FrameEvent& e) { return std::to_string(e.pos.offset); }},
    {"header", [](const FrameEvent& e) { return std::string(frame_of(e).header_text()); }},
    {"src", [](const FrameEvent& e) { return char_cell(frame_of(e).src); }},
    {"dst", [](const FrameEvent& e) { return char_cell(frame_of(e).dst); }},
    {"control",
     [](const FrameEvent& e) {
       const char c = frame_of(e).control;
       return c ? char_cell(c) : std::string();
     }},
    {"ident", [](const FrameEvent& e) { return escape(frame_of(e).ident_view()); }},
    {"data", [](const FrameEvent& e) { return escape(frame_of(e).data()); }},
    {"raw", [](const FrameEvent& e) { return escape(frame_of(e).raw); }},
    {"checksum_ok",
     [](const FrameEvent& e) { return std::string(frame_of(e).checksum_ok ? "true" : "false"); }},
    {"dialect",
     [](const FrameEvent& e) { return std::string(top::to_string(decoded_of(e).dialect)); }},
    {"role", [](const FrameEvent& e) { return std::string(top::to_string(decoded_of(e).role)); }},
    {"title",
     [](const FrameEvent& e) {
       const top::CommandSpec* c = decoded_of(e).command;
       return c ? std::string(c->title) : std::string();
     }},
    {"summary", [](const FrameEvent& e) { return decoded_of(e).summary(); }},
    {"findings",
     [](const FrameEvent& e) {
       std::string v;
       for (const top::Finding* x : all_findings(frame_of(e), decoded_of(e)))
         v += (v.empty() ? "" : ";") + std::string(top::to_string(x->code));
       for (const Note& n : e.notes) v += (v.empty() ? "" : ";") + std::string(to_string(n.code));
       return v;
     }},
    {"severity", [](const FrameEvent& e) { return std::string(top::to_string(e.worst())); }},
    {"ok",
     [](const FrameEvent& e) {
       return std::string(e.worst() == top::Severity::error ? "false" : "true");
     }},
    {"reply_to",
     [](const FrameEvent& e) { return e.reply_to ? std::to_string(e.reply_to) : std::string(); }},
    {"latency_ms",
     [](const FrameEvent& e) {
       if (e.latency_us < 0) return std::string();
       char b[32];
       std::snprintf(b, sizeof b, "%.3f", static_cast<double>(e.latency_us) / 1000.0);
       return std::string(b);
     }},
};

constexpr std::string_view kField = "field.";

int column_index(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kColumns); ++i)
    if (kColumns[i].name == name) return static_cast<int>(i);
  return -1;
}

void csv_cell(std::string& o, std::string_view v) {
  if (v.find_first_of(",\"\n\r") == std::string_view::npos) {
    o += v;
    return;
  }
  o += '"';
  for (char c : v) {
    if (c == '"') o += '"';
    o += c;
  }
  o += '"';
}

}  // namespace

const std::vector<std::string>& csv_columns() {
  static const std::vector<std::string> c = [] {
    std::vector<std::string> v;
    for (const Column& x : kColumns) v.emplace_back(x.name);
    return v;
  }();
  return c;
}

bool csv_column_ok(const std::string& c) {
  return (c.rfind(kField, 0) == 0 && c.size() > kField.size()) || column_index(c) >= 0;
}

CsvSink::CsvSink(Out& out, const std::vector<std::string>& columns) : out_(out) {
  std::string& o = out_.buf();
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const std::string& c = columns[i];
    o += (i ? "," : "") + c;
    const int k = column_index(c);
    cols_.push_back(k);
    fields_.push_back(k < 0 && c.rfind(kField, 0) == 0 ? c.substr(kField.size()) : std::string());
  }
  o += '\n';
}

void CsvSink::frame(const FrameEvent& e) {
  std::string& o = out_.buf();
  for (std::size_t i = 0; i < cols_.size(); ++i) {
    if (i) o += ',';
    std::string v;
    if (cols_[i] >= 0) {
      v = kColumns[static_cast<std::size_t>(cols_[i])].cell(e);
    } else {
      for (const auto& fv : decoded_of(e).fields)
        if (fv.name() == fields_[i]) v = format_value(fv);
    }
    csv_cell(o, v);
  }
  o += '\n';
  out_.done();
}

}  // namespace topdump
