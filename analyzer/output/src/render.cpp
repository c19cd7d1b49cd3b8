#include "output/render.hpp"

#include <algorithm>
#include <cstdio>

#include "output/escape.hpp"
#include "top/detail/text.hpp"

namespace topdump {

std::vector<const top::Finding*> all_findings(const top::Frame& f, const top::Decoded& d) {
  std::vector<const top::Finding*> v;
  v.reserve(f.findings.size() + d.findings.size());
  for (const auto& x : f.findings) v.push_back(&x);
  for (const auto& x : d.findings) v.push_back(&x);
  const auto by_offset = [](const top::Finding* a, const top::Finding* b) {
    return a->offset < b->offset;
  };
  // Stably: by insertion for the few findings a frame has (std::stable_sort
  // allocates a buffer on every call).
  if (v.size() > 32) {
    std::stable_sort(v.begin(), v.end(), by_offset);
    return v;
  }
  for (std::size_t i = 1; i < v.size(); ++i)
    for (std::size_t j = i; j > 0 && by_offset(v[j], v[j - 1]); --j) std::swap(v[j], v[j - 1]);
  return v;
}

top::Severity worst(const top::Frame& f, const top::Decoded& d) {
  top::Severity w = f.worst();
  for (const auto& x : d.findings)
    if (x.severity > w) w = x.severity;
  return w;
}

std::string address_name(char a) {
  const std::string_view what = top::describe_address(a);
  if (what.empty()) return escape(std::string(1, a));
  return top::cat({std::string_view(&a, 1), " (", what, ")"});
}

namespace {

std::string hex2(std::uint8_t v) {
  char b[3];
  top::put_hex2(v, b);
  b[2] = 0;
  return b;
}

}  // namespace

std::string finding_line(const top::Finding& x) {
  char b[32];
  std::snprintf(b, sizeof b, "%-7s ", std::string(top::to_string(x.severity)).c_str());
  std::string s = b;
  s += top::to_string(x.code);
  s += " @" + std::to_string(x.offset) + ": " + x.message;
  if (!x.quirk.empty()) s += " [quirk: " + std::string(x.quirk) + "]";
  return s;
}

std::string frame_tree(const top::Frame& f, const top::Decoded& d) {
  std::string s;
  auto line = [&](const std::string& t) { s += "  " + t + "\n"; };
  line("header   " + escape(f.header_text()) + " (" + std::string(top::describe(f.header)) +
       ")   @0");
  line("src      " + address_name(f.src));
  line("dst      " + address_name(f.dst));
  std::string len = "length   " + std::to_string(f.data_length);
  if (f.declared_length != f.data_length)
    len += " (declared " + std::to_string(f.declared_length) + ")";
  line(len);
  if (f.control)
    line(std::string("control  ") + f.control + (f.control == 'r' ? " (query)" : " (set/control)"));
  std::string id = "ident    " + std::string(f.ident_view());
  if (d.command)
    id += ": " + std::string(d.command->title) + " [" + std::string(d.command->section) + ", " +
          std::string(top::to_string(d.dialect)) + " " + std::string(top::to_string(d.role)) + "]";
  line(id);
  line("data     \"" + escape(f.data()) + "\"");
  std::size_t width = 0;
  for (const auto& v : d.fields) width = std::max(width, top::field_key(v).size());
  for (const auto& v : d.fields) {
    std::string n = top::field_key(v);
    n.resize(width, ' ');
    line("  " + n + "  " + format_value(v) + "   @" + std::to_string(v.offset) + " \"" +
         escape(std::string_view(f.raw).substr(v.offset, v.length)) + "\"");
  }
  if (f.checksum_present) {
    std::string c = "checksum " + escape(f.checksum_text());
    c += f.checksum_ok ? " (ok)" : " (expected " + hex2(f.expected_checksum) + ")";
    line(c);
  } else {
    line("checksum missing (expected " + hex2(f.expected_checksum) + ")");
  }
  for (const top::Finding* x : all_findings(f, d)) line(finding_line(*x));
  return s;
}

}  // namespace topdump
