// read --csv: one row per event (frame, garbage, finding), the columns
// chosen from one table (docs/topdump-csv.md lists it; a test keeps the
// two in step).
#include <algorithm>
#include <cstdio>
#include <set>

#include "capture/sources.hpp"
#include "output/escape.hpp"
#include "output/output.hpp"

namespace topdump {

// One event of any kind; exactly one pointer is set.
struct CsvRow {
  const FrameEvent* f = nullptr;
  const GarbageEvent* g = nullptr;
  const NoteEvent* n = nullptr;

  template <class F>
  auto common(F&& get) const {
    return f ? get(*f) : g ? get(*g) : get(*n);
  }
  const top::Frame* frame() const { return f ? f->entry->frame : nullptr; }
  const top::Decoded* decoded() const { return f ? &f->entry->decoded : nullptr; }
};

namespace {

using Row = CsvRow;

using Cell = std::string (*)(const Row&);

std::string char_cell(char c) { return escape(std::string_view(&c, 1)); }
std::string num(std::uint64_t v) { return std::to_string(v); }
std::string text(const std::string* s) { return s ? *s : std::string(); }

// A cell read from a frame's bytes (`Get` takes the top::Frame) or from its
// decoding (the top::Decoded); "" for other rows.
template <auto Get>
std::string frame_cell(const Row& r) {
  return r.f ? Get(*r.frame()) : std::string();
}
template <auto Get>
std::string decoded_cell(const Row& r) {
  return r.f ? Get(*r.decoded()) : std::string();
}

// The codes (or messages) of a row's findings: a frame's frame, catalog
// and session findings, a garbage run's one, a finding row's own.
template <class F>
std::string each_finding(const Row& r, F&& part) {
  std::string v;
  auto add = [&](std::string_view code, std::string_view message) {
    if (!v.empty()) v += ';';
    v += part(code, message);
  };
  if (r.f) {
    for (const top::Finding* x : all_findings(*r.frame(), *r.decoded()))
      add(top::to_string(x->code), x->message);
    for (const Note& n : r.f->notes) add(to_string(n.code), n.message);
  } else if (r.g) {
    add(top::to_string(r.g->item->finding.code), r.g->item->finding.message);
  } else {
    add(to_string(r.n->note.code), r.n->note.message);
  }
  return v;
}

std::string code_cell(const Row& r) {
  return each_finding(r, [](std::string_view c, std::string_view) { return std::string(c); });
}

// The worst severity of a row's findings; "" for a frame without any.
std::string severity_cell(const Row& r) {
  if (r.f) {
    const bool any =
        !r.f->notes.empty() || !r.frame()->findings.empty() || !r.decoded()->findings.empty();
    return any ? std::string(top::to_string(r.f->worst())) : std::string();
  }
  return std::string(top::to_string(r.g ? r.g->item->finding.severity : r.n->note.severity));
}

struct Column {
  std::string_view name;
  Cell cell;
  std::string_view alias = {};  // the JSON key of the same value, when named otherwise
};

// Every column, in the order --csv lists them (docs/topdump-csv.md).
const Column kColumns[] = {
    {"type", [](const Row& r) { return std::string(r.f   ? "frame"
                                                   : r.g ? "garbage"
                                                         : "finding"); }},
    {"n", [](const Row& r) { return r.f ? num(r.f->n) : std::string(); }},
    {"time",
     [](const Row& r) {
       const std::int64_t ts = r.common([](const auto& e) { return e.ts; });
       return ts == kNoTime ? std::string() : format_time(ts);
     }},
    {"transport",
     [](const Row& r) {
       if (r.n && !r.n->from) return std::string();
       return std::string(to_string(r.common([](const auto& e) { return e.transport; })));
     }},
    {"from", [](const Row& r) { return text(r.common([](const auto& e) { return e.from; })); }},
    {"to", [](const Row& r) { return text(r.common([](const auto& e) { return e.to; })); }},
    {"conversation",
     [](const Row& r) {
       if (r.n && !r.n->conv) return std::string();
       return num(r.common([](const auto& e) { return e.conv_id(); }));
     }},
    {"record",
     [](const Row& r) { return num(r.common([](const auto& e) { return e.pos.record; })); }},
    {"index",
     [](const Row& r) {
       return r.n ? std::string() : num(r.common([](const auto& e) { return e.pos.index; }));
     }},
    {"offset",
     [](const Row& r) { return num(r.common([](const auto& e) { return e.pos.offset; })); }},
    {"stream_offset", [](const Row& r) { return r.f ? num(r.f->stream_offset) : std::string(); }},
    {"header", frame_cell<[](const top::Frame& f) { return std::string(f.header_text()); }>},
    {"src", frame_cell<[](const top::Frame& f) { return char_cell(f.src); }>},
    {"dst", frame_cell<[](const top::Frame& f) { return char_cell(f.dst); }>},
    {"length",
     [](const Row& r) {
       if (r.g) return num(r.g->item->length);
       return frame_cell<[](const top::Frame& f) { return num(f.data_length); }>(r);
     }},
    {"declared_length", frame_cell<[](const top::Frame& f) { return num(f.declared_length); }>},
    {"control", frame_cell<[](const top::Frame& f) {
       return f.control ? char_cell(f.control) : std::string();
     }>},
    {"ident", frame_cell<[](const top::Frame& f) { return escape(f.ident_view()); }>},
    {"data", frame_cell<[](const top::Frame& f) { return escape(f.data()); }>},
    {"checksum", frame_cell<[](const top::Frame& f) {
       return f.checksum_present ? escape(f.checksum_text()) : std::string();
     }>},
    {"checksum_ok",
     frame_cell<[](const top::Frame& f) { return std::string(f.checksum_ok ? "true" : "false"); }>},
    {"expected_checksum", frame_cell<[](const top::Frame& f) {
       char b[3];
       top::put_hex2(f.expected_checksum, b);
       return std::string(b, 2);
     }>},
    {"raw", frame_cell<[](const top::Frame& f) { return escape(f.raw); }>},
    {"preview", [](const Row& r) { return r.g ? escape(r.g->item->preview) : std::string(); }},
    {"dialect",
     decoded_cell<[](const top::Decoded& d) { return std::string(top::to_string(d.dialect)); }>},
    {"role",
     decoded_cell<[](const top::Decoded& d) { return std::string(top::to_string(d.role)); }>},
    {"title", decoded_cell<[](const top::Decoded& d) {
       return d.command ? std::string(d.command->title) : std::string();
     }>,
     "command"},
    {"section", decoded_cell<[](const top::Decoded& d) {
       return d.command ? std::string(d.command->section) : std::string();
     }>},
    {"summary", decoded_cell<[](const top::Decoded& d) { return d.summary(); }>},
    {"findings", code_cell, "code"},
    {"messages",
     [](const Row& r) {
       return each_finding(r, [](std::string_view, std::string_view m) { return std::string(m); });
     },
     "message"},
    {"severity", severity_cell},
    {"quirks",
     [](const Row& r) {
       std::string v;
       if (r.f)
         for (const top::Finding* x : all_findings(*r.frame(), *r.decoded()))
           if (!x->quirk.empty()) v += (v.empty() ? "" : ";") + std::string(x->quirk);
       return v;
     }},
    {"session",
     [](const Row& r) {
       std::string v;
       if (r.f)
         for (const Note& n : r.f->notes)
           v += (v.empty() ? "" : ";") + std::string(to_string(n.code));
       return v;
     }},
    {"ok",
     [](const Row& r) {
       if (r.n) return std::string();
       const top::Severity w = r.f ? r.f->worst() : r.g->item->finding.severity;
       return std::string(w == top::Severity::error ? "false" : "true");
     }},
    {"reply_to",
     [](const Row& r) { return r.f && r.f->reply_to ? num(r.f->reply_to) : std::string(); }},
    {"latency_ms",
     [](const Row& r) {
       if (!r.f || r.f->latency_us < 0) return std::string();
       char b[32];
       std::snprintf(b, sizeof b, "%.3f", static_cast<double>(r.f->latency_us) / 1000.0);
       return std::string(b);
     }},
    {"copy_of",
     [](const Row& r) { return r.f && r.f->copy_of ? num(r.f->copy_of) : std::string(); }},
    {"frame",
     [](const Row& r) { return r.n && r.n->note.frame ? num(r.n->note.frame) : std::string(); }},
};

constexpr std::string_view kField = "field.";
constexpr std::string_view kUnit = ".unit";

int column_index(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kColumns); ++i)
    if (kColumns[i].name == name || (!kColumns[i].alias.empty() && kColumns[i].alias == name))
      return static_cast<int>(i);
  return -1;
}

// Every field name of the catalog, both dialects.
const std::set<std::string, std::less<>>& field_names() {
  static const std::set<std::string, std::less<>> names = [] {
    std::set<std::string, std::less<>> v;
    for (top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek})
      for (const top::CommandSpec& c : top::commands(d))
        for (const top::FormSpec& f : c.forms) {
          for (const top::FieldSpec& x : f.fields) v.emplace(x.name);
          for (const top::FieldSpec& x : f.record) v.emplace(x.name);
        }
    return v;
  }();
  return names;
}

// A field column's name without its record number ("x[2]": x), as the
// catalog names the field (top::field_key).
std::string_view without_record(std::string_view key) {
  if (key.size() < 4 || key.back() != ']') return key;
  const std::size_t open = key.rfind('[');
  if (open == std::string_view::npos || open == 0 || open + 2 >= key.size()) return key;
  for (std::size_t i = open + 1; i + 1 < key.size(); ++i)
    if (key[i] < '0' || key[i] > '9') return key;
  return key.substr(0, open);
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

std::vector<std::string> csv_aliases() {
  std::vector<std::string> v;
  for (const Column& x : kColumns)
    if (!x.alias.empty()) v.push_back(std::string(x.alias) + "=" + std::string(x.name));
  return v;
}

std::string csv_column_error(const std::string& c) {
  if (column_index(c) >= 0) return {};
  if (c.rfind(kField, 0) == 0) {
    std::string_view name = std::string_view(c).substr(kField.size());
    if (name.size() > kUnit.size() && name.substr(name.size() - kUnit.size()) == kUnit &&
        !field_names().count(name))
      name.remove_suffix(kUnit.size());
    if (field_names().count(without_record(name))) return {};
    std::string all;
    for (const auto& n : field_names()) all += (all.empty() ? "" : ", ") + n;
    return "unknown field \"" + std::string(name) + "\" in column \"" + c +
           "\"; the catalog's fields are: " + all;
  }
  std::string all;
  for (const auto& n : csv_columns()) all += (all.empty() ? "" : ", ") + n;
  for (const auto& n : csv_aliases()) all += ", " + n;
  return "unknown column \"" + c + "\"; the columns are: " + all +
         ", field.NAME and field.NAME.unit";
}

CsvSink::CsvSink(Out& out, const std::vector<std::string>& columns) : out_(out) {
  std::string& o = out_.buf();
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const std::string& c = columns[i];
    o += (i ? "," : "") + c;
    const int k = column_index(c);
    cols_.push_back(k);
    std::string field = k < 0 && c.rfind(kField, 0) == 0 ? c.substr(kField.size()) : std::string();
    bool unit = false;
    if (field.size() > kUnit.size() && field.ends_with(kUnit) && !field_names().count(field)) {
      field.resize(field.size() - kUnit.size());
      unit = true;
    }
    fields_.push_back(std::move(field));
    units_.push_back(unit);
  }
  o += '\n';
  out_.head();
}

void CsvSink::row(const CsvRow& r, std::int64_t ts, std::uint64_t record) {
  std::string& o = out_.buf();
  std::string v;
  for (std::size_t i = 0; i < cols_.size(); ++i) {
    if (i) o += ',';
    v.clear();
    if (cols_[i] >= 0) {
      v = kColumns[static_cast<std::size_t>(cols_[i])].cell(r);
    } else if (r.f) {
      // NAME: the first field so named (a record's: the first record's);
      // NAME[n]: that of record n
      for (const auto& fv : r.f->entry->decoded.fields)
        if (fv.name() == fields_[i] || (fv.record && top::field_key(fv) == fields_[i])) {
          if (units_[i])
            v = fv.unit();
          else
            top::append_plain_value(fv, v);
          break;
        }
    }
    csv_cell(o, v);
  }
  o += '\n';
  out_.done(ts, record);
}

void CsvSink::frame(const FrameEvent& e) { row(CsvRow{&e, nullptr, nullptr}, e.ts, e.pos.record); }
void CsvSink::garbage(const GarbageEvent& e) {
  row(CsvRow{nullptr, &e, nullptr}, e.ts, e.pos.record);
}
void CsvSink::note(const NoteEvent& e) { row(CsvRow{nullptr, nullptr, &e}, e.ts, e.pos.record); }

}  // namespace topdump
