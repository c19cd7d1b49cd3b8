// Reading serial logs line by line (capture's own header): the line
// reader, the shapes of a line that format detection also looks for, and
// the text of a log-syntax note.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <istream>
#include <streambuf>
#include <string>
#include <string_view>

#include "capture/sink.hpp"

namespace topdump {

inline bool is_socat_header(std::string_view l) {
  // "> 2026/11/22 05:32:42.000581031  length=19 from=0 to=18"
  return l.size() > 24 && (l[0] == '>' || l[0] == '<') && l[1] == ' ' && l[6] == '/' &&
         l[9] == '/' && l.find("length=") != std::string_view::npos;
}

inline std::string_view first_line(std::string_view s) {
  auto e = s.find('\n');
  std::string_view l = s.substr(0, e);
  if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
  return l;
}

// "<ISO time> <TX|RX> <frame>"
inline bool split_line_log(std::string_view l, std::string_view& time, std::string_view& dir,
                           std::string_view& rest) {
  auto a = l.find(' ');
  if (a == std::string_view::npos) return false;
  auto b = l.find(' ', a + 1);
  if (b == std::string_view::npos) return false;
  time = l.substr(0, a);
  dir = l.substr(a + 1, b - a - 1);
  rest = l.substr(b + 1);
  return dir == "TX" || dir == "RX";
}

inline Endpoint named(std::string n) {
  Endpoint e;
  e.name = std::move(n);
  return e;
}

// A streambuf over a FILE (an Input's, which may be a pipe).
class FileBuf : public std::streambuf {
 public:
  explicit FileBuf(std::FILE* f) : f_(f) {}

 private:
  int_type underflow() override {
    const std::size_t n = std::fread(buf_.data(), 1, buf_.size(), f_);
    if (n == 0) return traits_type::eof();
    setg(buf_.data(), buf_.data(), buf_.data() + n);
    return traits_type::to_int_type(buf_[0]);
  }
  std::FILE* f_;
  std::array<char, 1 << 16> buf_;  // not zeroed: only what fread wrote is read
};

struct LineReader {
  explicit LineReader(std::FILE* f) : buf(f), in(&buf) {}
  FileBuf buf;
  std::istream in;
  std::string line;
  std::uint64_t number = 0;
  std::uint64_t offset = 0;  // file offset of the current line
  std::uint64_t next = 0;
  bool get() {
    if (!std::getline(in, line)) return false;
    ++number;
    offset = next;
    next += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
};

// "PATH: line N: " and the pieces, in one allocation (a chain of operator+
// made one per piece: a fuzzed log is mostly such notes).
std::string line_note(const std::string& path, std::uint64_t line,
                      std::initializer_list<std::string_view> why);

}  // namespace topdump
