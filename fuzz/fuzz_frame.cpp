// Target: one buffer that should hold one frame (parse_exact), decoded in
// every dialect. Checks the frame model's invariants, that the parse
// verdict does not depend on whether more bytes may follow nor on whether
// messages are written.
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>

#include "check.hpp"
#include "mutator.hpp"
#include "reuse.hpp"
#include "top/detail/parse_paths.hpp"
#include "top/top.hpp"

using namespace top;
using topfuzz::show;

namespace {

std::string describe(const Frame& f) {
  return "raw=\"" + show(f.raw) + "\" data_offset=" + std::to_string(f.data_offset) +
         " data_length=" + std::to_string(f.data_length);
}

void check_frame(std::string_view in, const Frame& f) {
  FUZZ_CHECK(f.raw.size() <= in.size() && in.substr(0, f.raw.size()) == f.raw,
             "raw is not a prefix of the input: " + describe(f));
  FUZZ_CHECK(std::size_t{f.data_offset} + f.data_length <= f.raw.size(),
             "data runs past the frame: " + describe(f));
  const std::size_t cs_at = std::size_t{f.data_offset} + f.data_length;
  // A double checksum (the C10 Pro tool's) belongs to the frame's bytes.
  FUZZ_CHECK(f.raw.size() == cs_at + (f.checksum_present ? 2 : 0) +
                                 (f.has(FindingCode::double_checksum) ? 2 : 0),
             "frame length is not data + checksum: " + describe(f));
  FUZZ_CHECK(f.expected_checksum == checksum(std::string_view(f.raw).substr(0, cs_at)),
             "expected_checksum is not the byte sum: " + describe(f));
  FUZZ_CHECK(f.checksum_ok == (f.checksum_present && f.checksum == f.expected_checksum),
             "checksum_ok disagrees with the digits: " + describe(f));
  FUZZ_CHECK(f.checksum_ok || f.has(FindingCode::bad_checksum) || f.has(FindingCode::no_checksum) ||
                 f.has(FindingCode::checksum_header_case),
             "a failing checksum without a finding that says so: " + describe(f));
  FUZZ_CHECK(!f.checksum_present || f.checksum_text().size() == 2,
             "checksum text is not two chars: " + describe(f));
  for (const Finding& x : f.findings) {
    FUZZ_CHECK(x.offset <= in.size(), "finding " + std::string(to_string(x.code)) + " offset " +
                                          std::to_string(x.offset) + " past the input of " +
                                          std::to_string(in.size()));
    FUZZ_CHECK(!x.message.empty(), "finding without a message");
  }
  FUZZ_CHECK(is_address(f.src) && is_address(f.dst),
             "addresses outside U M D E P G: " + describe(f));
}

void check_decoded(const Frame& f, const Decoded& d) {
  static std::string text = topfuzz::reused_text();
  for (const FieldValue& v : d.fields) {
    FUZZ_CHECK(v.spec != nullptr, "field without a spec");
    FUZZ_CHECK(v.offset >= f.data_offset &&
                   std::size_t{v.offset} + v.length <= std::size_t{f.data_offset} + f.data_length,
               "field " + std::string(v.name()) + " outside the data: " + describe(f));
    text.clear();
    append_value(v, text);  // format_value() without a string per field
  }
  FUZZ_CHECK(d.form == nullptr || d.command != nullptr, "a form without a command");
  FUZZ_CHECK(d.fields.empty() || d.form != nullptr, "fields without a form");
  for (const Finding& x : d.findings)
    FUZZ_CHECK(x.offset <= f.raw.size() + 2, "decode finding " + std::string(to_string(x.code)) +
                                                 " past the frame: " + describe(f));
  (void)d.summary();
}

// Two parses that found the same frame: raw bytes, and the codes and
// offsets of the first `findings` findings.
bool same_frame(const ParseResult& a, const ParseResult& b, std::size_t findings) {
  if (a.status != ParseStatus::frame || b.status != ParseStatus::frame ||
      a.frame.raw != b.frame.raw || a.frame.findings.size() < findings ||
      b.frame.findings.size() < findings)
    return false;
  for (std::size_t i = 0; i < findings; ++i)
    if (a.frame.findings[i].code != b.frame.findings[i].code ||
        a.frame.findings[i].offset != b.frame.findings[i].offset)
      return false;
  return true;
}

// The verdicts on `in` with more bytes possibly to come (`open`) and at
// the end of input (`closed`).
void check_open_closed(std::string_view in, const ParseResult& open, const ParseResult& closed) {
  // The verdict with more bytes possibly to come is either "need more" or
  // the verdict at the end.
  // One exception: the two digits of a second checksum at the very end (the
  // C10 Pro tool's double checksum) join the frame only at the end of input;
  // before it, the stream decoder gives them to the frame it holds when the
  // byte after them comes (detail::take_second_checksum).
  const bool second_at_end = open.status == ParseStatus::frame &&
                             closed.status == ParseStatus::frame &&
                             closed.frame.has(FindingCode::double_checksum) &&
                             !open.frame.has(FindingCode::double_checksum);
  if (second_at_end) {
    FUZZ_CHECK(closed.consumed == open.consumed + 2 && closed.consumed == in.size() &&
                   closed.frame.raw == open.frame.raw + std::string(in.substr(open.consumed, 2)) &&
                   closed.frame.findings.size() == open.frame.findings.size() + 1 &&
                   closed.frame.findings.back().code == FindingCode::double_checksum,
               "a second checksum at the end of input changed more than the frame's end: \"" +
                   show(in) + "\"");
  } else if (open.status == ParseStatus::frame) {
    FUZZ_CHECK(closed.consumed == open.consumed &&
                   same_frame(open, closed, closed.frame.findings.size()) &&
                   open.frame.findings.size() == closed.frame.findings.size(),
               "a frame found before the end differs at the end of input: \"" + show(in) + "\"");
  } else if (open.status == ParseStatus::invalid) {
    FUZZ_CHECK(closed.status == ParseStatus::invalid && closed.error.code == open.error.code &&
                   closed.error.offset == open.error.offset,
               "an invalid verdict changed at the end of input: \"" + show(in) + "\"");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  size = topfuzz::capped(size);
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  // Kept across inputs (reuse.hpp).
  static ParseResult r = topfuzz::reused_parse_result(), open = topfuzz::reused_parse_result(),
                     closed = topfuzz::reused_parse_result(), slow = topfuzz::reused_parse_result();
  static Decoded decoded = topfuzz::reused_decoded();
  const topfuzz::ReleaseAtEnd release(r, open, closed, slow, decoded);
  const ParseOptions defaults;
  parse_exact(in, defaults, r);
  FUZZ_CHECK(r.status != ParseStatus::need_more, "parse_exact asked for more bytes");

  // The parses below write no messages (as the stream decoder parses inside
  // a frame): the texts come from parse_exact above, and each parse without
  // them must give its verdict, codes and offsets.
  ParseOptions no_text;
  no_text.messages = false;
  parse_frame(in, false, no_text, open);
  parse_frame(in, true, no_text, closed);
  FUZZ_CHECK(closed.status != ParseStatus::need_more, "at_end parse asked for more bytes");
  check_open_closed(in, open, closed);
  // With messages (parse_exact: the parse at the end, then any CR/LF and
  // trailing-bytes findings) the same verdict, codes and offsets.
  bool same_texts = r.status == closed.status;
  if (same_texts && r.status == ParseStatus::frame)
    same_texts = same_frame(r, closed, closed.frame.findings.size());
  else if (same_texts)
    same_texts = r.error.code == closed.error.code && r.error.offset == closed.error.offset;
  FUZZ_CHECK(same_texts, "parses with and without messages differ on \"" + show(in) + "\"");
  for (const ParseResult* q : {&open, &closed}) {
    bool quiet = q->error.message.empty();
    for (const Finding& x : q->frame.findings) quiet = quiet && x.message.empty();
    FUZZ_CHECK(quiet, "a parse without messages wrote one on \"" + show(in) + "\"");
  }

  // The one-pass path for clean frames builds what the general parse builds.
  for (const ParseResult* fast : {&open, &closed}) {
    detail::parse_frame_general(in, fast == &closed, no_text, slow);
    bool same = slow.status == fast->status && slow.consumed == fast->consumed;
    if (same && slow.status == ParseStatus::frame) {
      const Frame &a = fast->frame, &b = slow.frame;
      same = a.header == b.header && a.src == b.src && a.dst == b.dst && a.control == b.control &&
             a.ident_view() == b.ident_view() && a.declared_length == b.declared_length &&
             a.data_offset == b.data_offset && a.data_length == b.data_length &&
             a.checksum == b.checksum && a.expected_checksum == b.expected_checksum &&
             a.checksum_present == b.checksum_present && a.checksum_ok == b.checksum_ok &&
             a.terminator == b.terminator && a.raw == b.raw &&
             a.findings.size() == b.findings.size();
      for (std::size_t i = 0; same && i < a.findings.size(); ++i)
        same = a.findings[i].code == b.findings[i].code &&
               a.findings[i].offset == b.findings[i].offset;
    }
    FUZZ_CHECK(same, "the one-pass parse and the general parse disagree on \"" + show(in) + "\"");
  }

  if (r.status == ParseStatus::invalid) {
    FUZZ_CHECK(r.error.offset <= size, "error offset past the input");
    FUZZ_CHECK(!r.error.message.empty(), "error without a message");
    return 0;
  }
  FUZZ_CHECK(r.consumed == size, "parse_exact did not account for every byte");
  const Frame& f = r.frame;
  check_frame(in, f);
  FUZZ_CHECK(closed.status == ParseStatus::frame && closed.frame.raw == f.raw,
             "parse_exact and parse_frame disagree on the frame");

  static constexpr DecodeOptions kOptions[] = {
      {Dialect::unknown, Model::unknown, Role::any},
      {Dialect::skydroid, Model::c12, Role::any},
      {Dialect::skydroid, Model::c10, Role::request},
      {Dialect::topotek, Model::sip, Role::any},
      {Dialect::topotek, Model::unknown, Role::response},
  };
  // Every way decodes the frame; with detail (fields, values, texts) the
  // auto-detected dialect and one of the other four, picked by the input's
  // length, the rest as `topdump stats` decodes (the verdict only).
  const std::size_t detailed = 1 + size % 4;
  for (std::size_t i = 0; i < std::size(kOptions); ++i) {
    DecodeOptions o = kOptions[i];
    o.detail = i == 0 || i == detailed;
    decode(f, o, decoded);
    check_decoded(f, decoded);
  }
  return 0;
}
