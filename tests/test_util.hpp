// Helpers shared by the tests.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "top/detail/decode_cache.hpp"
#include "top/top.hpp"

namespace toptest {

// Every item of a byte stream fed in one piece.
inline std::vector<top::StreamItem> decode_all(std::string_view bytes,
                                               const top::StreamOptions& opts = {}) {
  top::StreamDecoder d(opts);
  d.feed(bytes);
  d.finish();
  std::vector<top::StreamItem> out;
  top::StreamItem it;
  while (d.next(it)) out.push_back(std::move(it));
  return out;
}

// Every item of a byte stream fed in chunks of the given sizes (cycled).
inline std::vector<top::StreamItem> decode_chunked(std::string_view bytes,
                                                   const std::vector<std::size_t>& sizes,
                                                   const top::StreamOptions& opts = {}) {
  top::StreamDecoder d(opts);
  std::vector<top::StreamItem> out;
  top::StreamItem it;
  std::size_t i = 0, k = 0;
  while (i < bytes.size()) {
    std::size_t n = std::min(sizes[k++ % sizes.size()], bytes.size() - i);
    d.feed(bytes.substr(i, n));
    i += n;
    while (d.next(it)) out.push_back(std::move(it));
  }
  d.finish();
  while (d.next(it)) out.push_back(std::move(it));
  return out;
}

// A copy of the bytes in a heap block of exactly their size, so ASan flags
// any read past the end.
struct ExactBuffer {
  explicit ExactBuffer(std::string_view s)
      : size(s.size()), data(new char[s.size() ? s.size() : 1]) {
    if (!s.empty()) std::memcpy(data.get(), s.data(), s.size());
  }
  std::string_view view() const { return {data.get(), size}; }
  std::size_t size;
  std::unique_ptr<char[]> data;
};

// A compact, comparable description of an item sequence.
inline std::string describe(const std::vector<top::StreamItem>& items) {
  std::string s;
  for (const auto& it : items) {
    s += "@" + std::to_string(it.offset) + "+" + std::to_string(it.length) + " ";
    if (it.kind == top::ItemKind::garbage) {
      s += "garbage:" + std::string(top::to_string(it.finding.code)) + "@" +
           std::to_string(it.finding.offset);
    } else {
      s += it.frame.raw + " [";
      for (const auto& f : it.frame.findings) s += std::string(top::to_string(f.code)) + " ";
      s += "] t" + std::to_string(it.frame.terminator);
    }
    s += "\n";
  }
  return s;
}

// A frame in Topotek 12.2's malformed TMP form (#PDP16TMP: header "#P",
// addresses D and P, length 0x16 = 22 data bytes), in 0.1 degC: hottest
// point x 0x0A0, y 0x64 at 0x01F4 (50.0), coldest x 0x140, y 0x20 at 0xFF38
// (-20.0), centre 0x0123 (29.1); checksum appended.
// Parses `bytes` as one frame (a test failure if it is not) and decodes it.
inline top::Decoded dec(std::string_view bytes, top::Dialect d = top::Dialect::unknown,
                        top::Model m = top::Model::unknown) {
  top::ParseResult r = top::parse_exact(bytes);
  EXPECT_EQ(r.status, top::ParseStatus::frame) << bytes;
  return top::decode(r.frame, {.dialect = d, .model = m});
}

// decode() as topdump stats decodes: through a shape cache
// (top/detail/decode_cache.hpp), used without detail only.
inline top::Decoded decode_cached(const top::Frame& f, const top::DecodeOptions& o,
                                  top::detail::DecodeCache& cache) {
  top::Decoded d;
  top::detail::decode(f, o, &cache, d);
  return d;
}

inline const top::FieldValue& field(const top::Decoded& d, std::string_view name) {
  for (const auto& f : d.fields)
    if (f.name() == name) return f;
  static top::FieldValue none;
  ADD_FAILURE() << "no field " << name << " in " << d.summary();
  return none;
}

inline std::string tmp_quirk_frame() {
  return top::with_checksum(
      "#PDP16TMP0A06401F4"
      "14020FF38"
      "0123");
}

inline bool has_code(const std::vector<top::Finding>& v, top::FindingCode c) {
  for (const auto& f : v)
    if (f.code == c) return true;
  return false;
}

}  // namespace toptest
