// Internal: what the two halves of the general frame parse share.
// frame_parse.cpp reads the header, addresses, length and identifier;
// frame_checksum.cpp judges the data and the checksum.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "byte_sum.hpp"
#include "chars.hpp"
#include "top/frame.hpp"

namespace top::detail {

// reset_keep_capacity, inline for the parser: it resets the frame of every
// general parse.
inline void reset_frame(Frame& f) noexcept {
  f.header = Header::variable;
  f.src = f.dst = f.control = 0;
  f.ident[0] = f.ident[1] = f.ident[2] = 0;
  f.declared_length = f.data_offset = f.data_length = 0;
  f.checksum = f.expected_checksum = 0;
  f.checksum_present = f.checksum_ok = false;
  f.terminator = 0;
  f.raw.clear();
  f.findings.clear();
}

inline std::string hex2(std::uint8_t v) {
  char b[2];
  put_hex2(v, b);
  return std::string(b, 2);
}

// A byte as a finding quotes it: 'x' when printable, else 0xNN.
inline std::string printable(char c) {
  auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7F) return {'\'', c, '\''};
  char b[8];
  std::snprintf(b, sizeof b, "0x%02X", u);
  return b;
}

inline bool is_boundary(char c) noexcept { return c == '#' || c == '\r' || c == '\n'; }

// A parse's verdict without its frame (built in place by the parse) or its
// error (written to the caller's Finding only when invalid).
struct Verdict {
  ParseStatus status = ParseStatus::need_more;
  std::size_t consumed = 0;
};

inline Verdict invalid(Finding& err, FindingCode code, std::size_t offset, std::string msg) {
  // In place, as make_finding would build it: the stream decoder parses at
  // every '#', most of them fail, and a Finding built and moved in costs more
  // than the parse.
  err.code = code;
  err.severity = default_severity(code);
  err.offset = static_cast<std::uint32_t>(offset);
  err.message = std::move(msg);
  err.quirk = {};
  return Verdict{ParseStatus::invalid, 0};
}

// `until`: the input length below which the verdict stays need_more (0
// when the parse cannot tell).
inline Verdict need_more(std::size_t until = 0) { return Verdict{ParseStatus::need_more, until}; }

inline Verdict truncated(Finding& err, std::size_t have, std::size_t want) {
  return invalid(err, FindingCode::truncated, have,
                 cat({"input ends after ", std::to_string(have), " bytes of a frame that needs ",
                      std::to_string(want)}));
}

// Checks the checksum digits at `p`: true when the two digits are hex
// (their value in `value`) and equal to prefix_sum, the sum of bytes [0, p).
inline bool checksum_at(std::string_view b, std::size_t p, unsigned prefix_sum,
                        std::uint8_t& value) noexcept {
  if (p + 2 > b.size()) return false;
  int hi = hex_value(b[p]), lo = hex_value(b[p + 1]);
  if (hi < 0 || lo < 0) return false;
  value = static_cast<std::uint8_t>(hi * 16 + lo);
  return value == static_cast<std::uint8_t>(prefix_sum & 0xFF);
}

// Two checksum digits at `end`, right after a frame's valid checksum (the
// sum of the bytes before that checksum: `prefix`), that are the sum of the
// frame with its checksum, followed by the end of input or a boundary: a
// double checksum (the C10 Pro tool's #TPUG2wPTZ056FEB). The fast path's
// test: true sends the frame to the general parse, which decides with
// take_second_checksum.
inline bool second_checksum(std::string_view b, std::size_t end, unsigned prefix,
                            std::uint8_t& value) noexcept {
  if (end + 2 > b.size() || end < 2) return false;
  if (end + 2 < b.size() && !is_boundary(b[end + 2])) return false;
  const unsigned sum =
      prefix + static_cast<unsigned char>(b[end - 2]) + static_cast<unsigned char>(b[end - 1]);
  return checksum_at(b, end, sum, value);
}

// Whether `rest`, the bytes after frame `f`, begins with its second checksum
// (see second_checksum): yes, no, or undecided while the bytes that came
// still agree and more may come (not `at_end`). On yes the two digits join
// the frame: its raw bytes and a double-checksum finding (texts when
// `messages`). The one home of the rule, for the parse (the bytes it has)
// and the stream decoder (the bytes that come after a frame it holds), so
// that the frame is the same however the stream is cut.
enum class SecondChecksum : std::uint8_t { no, yes, undecided };
SecondChecksum take_second_checksum(Frame& f, std::string_view rest, bool at_end, bool messages);

// Where the parts of a frame lie, as its header and length field say.
struct Layout {
  Header header = Header::variable;
  char control = 0;
  std::size_t ident_at = 7;
  std::size_t data_at = prefix_size;
  std::size_t declared = 0;
  bool hex_length = true;  // length is hex digits (alternatives make sense)
  bool two_digit = false;
};

// One general parse: its input, options, the frame built in `f` and the
// error written to `err`, and the layout read so far.
struct Parse {
  std::string_view b;
  bool at_end;
  const ParseOptions& opts;
  Frame& f;
  Finding& err;
  std::size_t n;  // b.size()
  Layout lay;

  // A finding's text, built only when the caller keeps it.
  template <class Build>
  std::string text(Build&& build) const {
    return opts.messages ? std::string(build()) : std::string();
  }
  Verdict cut(std::size_t have, std::size_t want) const {
    return opts.messages ? truncated(err, have, want)
                         : invalid(err, FindingCode::truncated, have, {});
  }
  // The input ends before byte `need`: need_more, or truncated (a frame
  // needs `want` bytes) at the end of input.
  Verdict more(std::size_t want) const { return at_end ? cut(n, want) : need_more(); }
};

// frame_checksum.cpp: the verdict on the data and checksum of a frame whose
// header, length and identifier `p` has read.
Verdict judge_checksum(Parse& p);

}  // namespace top::detail
