// Frames of the TOP protocol: model, parser, checksum and builder.
//
//   #tp  U G  6  w  GAY  EF0732  88
//   hdr  src dst len ctl ident data checksum
//
// Nothing here allocates beyond the frame's own bytes, prints or throws.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "top/findings.hpp"

namespace top {

// The header family.
enum class Header : std::uint8_t {
  fixed,     // #TP  one hex length char, documented length 2
  variable,  // #tp  one hex length char, 0-F
  ext8,      // #tP  one raw length byte, 0-255 (Topotek)
  ext16,     // #Tp  two raw big-endian length bytes in place of len+control
  tmp_quirk  // #PDP16TMP... the malformed Topotek TMP form (no 'tp', no ctl)
};

std::string_view to_string(Header h) noexcept;  // "#TP", "#tp", "#tP", "#Tp", "#P"
std::optional<Header> header_from_string(std::string_view s) noexcept;
// What the header means: "fixed, length 2", "variable, one hex length char", ...
std::string_view describe(Header h) noexcept;

// Hard limits of the format.
inline constexpr std::size_t max_data_hex = 0x0F;
inline constexpr std::size_t max_data_ext8 = 0xFF;
inline constexpr std::size_t max_data_ext16 = 0xFFFF;
// Bytes before the data of a #TP/#tp/#tP frame: # t p S D L C I I I.
inline constexpr std::size_t prefix_size = 10;
// Largest frame of any header: "#Tp" SD LL III data(65535) CC.
inline constexpr std::size_t max_frame_size = 3 + 2 + 2 + 3 + max_data_ext16 + 2;

namespace detail {
// Character classes of the frame syntax, one table lookup each: the parser
// tests several per frame, and a chain of compares costs more (and under
// the fuzzers' comparison tracing, much more).
enum : std::uint8_t { kClassAddress = 1, kClassIdent = 2, kClassLowerHex = 4 };
inline constexpr std::array<std::uint8_t, 256> kCharClass = [] {
  std::array<std::uint8_t, 256> t{};
  for (const char c : {'U', 'M', 'D', 'E', 'P', 'G'})
    t[static_cast<unsigned char>(c)] |= kClassAddress;
  for (int c = 'A'; c <= 'Z'; ++c) t[static_cast<std::size_t>(c)] |= kClassIdent;
  for (int c = '0'; c <= '9'; ++c) t[static_cast<std::size_t>(c)] |= kClassIdent;
  for (int c = 'a'; c <= 'f'; ++c) t[static_cast<std::size_t>(c)] |= kClassLowerHex;
  return t;
}();
inline bool char_is(char c, std::uint8_t cls) noexcept {
  return (kCharClass[static_cast<unsigned char>(c)] & cls) != 0;
}
}  // namespace detail

// True for the address characters the documents define (U M D E P G).
inline bool is_address(char c) noexcept { return detail::char_is(c, detail::kClassAddress); }
// True for an identifier character: an uppercase letter or a digit.
inline bool is_ident_char(char c) noexcept { return detail::char_is(c, detail::kClassIdent); }
// What an address stands for (DESIGN.md, "The frame"): "UART/UDP client"
// for U, "lens" for M, ...; empty for a byte that is not an address.
std::string_view describe_address(char a) noexcept;
// True for a client-side address: U (UART/UDP client) or P (network client).
inline bool is_client_address(char c) noexcept { return c == 'U' || c == 'P'; }

// The most CR/LF bytes a frame's terminator counts (Frame::terminator is a
// uint8_t). The stream decoder makes any more that follow a garbage run after
// the frame, so every byte of a stream belongs to exactly one item.
inline constexpr std::size_t kMaxTerminator = 255;

// A parsed frame. `raw` holds exactly the frame's bytes (no terminator).
struct Frame {
  Header header = Header::variable;
  char src = 0;
  char dst = 0;
  char control = 0;  // 'r', 'w', or 0 for #Tp and the TMP form
  char ident[3] = {0, 0, 0};
  std::uint32_t declared_length = 0;   // what the length field says
  std::uint32_t data_offset = 0;       // where the data starts in raw
  std::uint32_t data_length = 0;       // the data length actually used
  std::uint8_t checksum = 0;           // value of the checksum digits
  std::uint8_t expected_checksum = 0;  // sum of the bytes before them
  bool checksum_present = false;       // two hex digits were there
  bool checksum_ok = false;            // present and equal (any case)
  std::uint8_t terminator = 0;         // CR/LF bytes that followed the frame (<= kMaxTerminator)
  std::string raw;
  std::vector<Finding> findings;

  std::string_view ident_view() const noexcept { return {ident, 3}; }
  std::string_view data() const noexcept {
    return std::string_view(raw).substr(data_offset, data_length);
  }
  std::string_view header_text() const noexcept {
    return std::string_view(raw).substr(0, header == Header::tmp_quirk ? 2 : 3);
  }
  std::string_view checksum_text() const noexcept;
  // True when no finding is an error.
  bool ok() const noexcept;
  // Highest severity among the findings (info when there are none).
  Severity worst() const noexcept;
  bool has(FindingCode c) const noexcept;
};

// Back to a default Frame, keeping the capacity of raw and findings: for a
// frame reused across parses.
void reset_keep_capacity(Frame& f) noexcept;
// Exchanges two frames: their buffers change hands, nothing is copied (the
// stream decoder hands frames out this way and reuses the buffers it gets).
void swap(Frame& a, Frame& b) noexcept;

// The TOP checksum: sum of the bytes, modulo 256.
std::uint8_t checksum(std::string_view bytes) noexcept;
// Two uppercase hex digits.
void put_hex2(std::uint8_t v, char out[2]) noexcept;
// The frame with its checksum appended: with_checksum("#TPUG2wGAA01") ==
// "#TPUG2wGAA0136".
std::string with_checksum(std::string_view without_checksum);

enum class ParseStatus : std::uint8_t {
  frame,      // a frame (possibly with findings) of `consumed` bytes
  need_more,  // the verdict depends on bytes not given yet
  invalid     // no frame starts at byte 0; `error` says why and where
};

struct ParseOptions {
  // Largest data length accepted from the length field.
  std::size_t max_data_length = max_data_ext16;
  // Try other data lengths when the declared one fails the checksum.
  bool recover_lying_length = true;
  // Write the text of the findings and of the error. False leaves every
  // message empty (codes, severities and offsets are the same): for callers
  // that look only at the verdict, such as the stream decoder trying a '#'
  // inside a frame.
  bool messages = true;
};

struct ParseResult {
  ParseStatus status = ParseStatus::need_more;
  // status == frame: the frame's bytes. need_more: the length of input
  // below which the verdict stays need_more, when the parse knows it (the
  // frame's header is complete), else 0.
  std::size_t consumed = 0;
  Frame frame;    // status == frame
  Finding error;  // status == invalid: code and offset of the fault
};

// Parses the frame that starts at bytes[0] (which should be '#').
// `at_end` says no more bytes will follow these, so a partial frame is
// reported as truncated rather than need_more. The result depends only on
// the bytes, never on how they were split.
ParseResult parse_frame(std::string_view bytes, bool at_end, const ParseOptions& opts = {});
// The same into `out`, reusing the capacity of its frame's raw bytes and
// findings (for loops over many frames: no allocation once warm). The frame
// is a default one unless the status is frame.
void parse_frame(std::string_view bytes, bool at_end, const ParseOptions& opts, ParseResult& out);

// Parses a buffer that should hold exactly one frame: a missing frame gives
// invalid, anything after the frame but CR/LF gives a trailing-bytes finding.
ParseResult parse_exact(std::string_view bytes, const ParseOptions& opts = {});
// The same into `out`, reusing its capacity as parse_frame does.
void parse_exact(std::string_view bytes, const ParseOptions& opts, ParseResult& out);

// How a frame is built.
struct BuildSpec {
  Header header = Header::variable;
  char src = 'U';
  char dst = 'G';
  char control = 'w';
  std::string_view ident;
  std::string_view data;
  bool lowercase_checksum = false;
  // Deliberate malformations, as real senders make them (topsim's faults and
  // firmware forms, topconf fuzz cases). Each leaves the frame otherwise
  // well formed.
  // The length written, when it is not the data's: a length that lies (the
  // C12 "#tpDU3rVER0105025A": length 3, six data chars). #TP/#tp write its
  // low hex digit, #tP its low byte, #Tp two bytes.
  std::optional<std::uint32_t> declared_length;
  // The header the checksum is summed over, when not the one written: the
  // SkyDroid GAY/GOT examples, summed as #tp and sent as #TP.
  std::optional<Header> checksum_header;
  // The length of a #tp frame as two hex digits: the Topotek 12.2 TMP
  // firmware form #tpDP16wTMP... (22 data chars).
  bool two_digit_length = false;
  // #TP/#tp kept past 15 data chars, its one hex digit then the low digit
  // of the length (or of declared_length), instead of switching to #tP.
  bool keep_header = false;
  // The checksum written instead of the sum: a wrong checksum.
  std::optional<std::uint8_t> checksum;
  // No checksum digits at all: the frame ends after its data.
  bool omit_checksum = false;
};

// Builds a frame with the header's length encoding and the checksum. The
// caller picks the header; see choose_header() in catalog.hpp for the
// dialect rules. A #TP/#tp frame with more than 15 data bytes is built as #tP
// (or #Tp past 255).
std::string build_frame(const BuildSpec& spec);
// The same into `out` (its old contents replaced, its storage kept): for a
// loop that builds a frame at a time.
void build_frame(const BuildSpec& spec, std::string& out);

}  // namespace top
