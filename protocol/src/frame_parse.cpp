// The frame parser: the common frame in one pass (parse_plain), and the
// general parse in named steps (the header, the addresses, the length and
// control, the identifier, the length's form), which hands the data and
// checksum to judge_checksum (frame_checksum.cpp); parse_exact's CR/LF and
// trailing bytes.
#include "frame_parse.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>

#include "top/detail/parse_paths.hpp"

namespace top {

namespace detail {

namespace {

// The common frame in one pass: #TP or #tp, two addresses, an uppercase hex
// length char, r or w, an identifier, the declared data and two uppercase
// checksum digits that match. These are exactly the frames on which the
// general parse below gives no finding and keeps the declared length, and it
// builds the same frame; false (with `f` untouched) sends every other input
// there.
bool parse_plain(std::string_view b, const ParseOptions& opts, Frame& f, Verdict& r) {
  const std::size_t n = b.size();
  if (n < prefix_size + 2 || b[0] != '#') return false;
  const bool fixed = b[1] == 'T' && b[2] == 'P';
  if (!fixed && !(b[1] == 't' && b[2] == 'p')) return false;
  const int len = hex_value(b[5]);
  if (!is_address(b[3]) || !is_address(b[4]) || len < 0 || is_lower_hex(b[5]) ||
      (b[6] != 'r' && b[6] != 'w') || !is_ident_char(b[7]) || !is_ident_char(b[8]) ||
      !is_ident_char(b[9]))
    return false;
  const auto L = static_cast<std::size_t>(len);
  const std::size_t cs = prefix_size + L;
  if (L > opts.max_data_length || n < cs + 2 || is_lower_hex(b[cs]) || is_lower_hex(b[cs + 1]))
    return false;
  const unsigned prefix = byte_sum8(b.data(), cs);  // cs >= prefix_size
  std::uint8_t value = 0;
  if (!checksum_at(b, cs, prefix, value)) return false;
  // A second checksum follows (double_checksum): the general parse's.
  if (std::uint8_t second = 0; n >= cs + 4 && second_checksum(b, cs + 2, prefix, second))
    return false;
  f.header = fixed ? Header::fixed : Header::variable;
  f.src = b[3];
  f.dst = b[4];
  f.control = b[6];
  f.ident[0] = b[7];
  f.ident[1] = b[8];
  f.ident[2] = b[9];
  f.declared_length = static_cast<std::uint32_t>(L);
  f.data_offset = static_cast<std::uint32_t>(prefix_size);
  f.data_length = static_cast<std::uint32_t>(L);
  f.checksum = f.expected_checksum = value;
  f.checksum_present = f.checksum_ok = true;
  f.terminator = 0;
  f.raw.resize(cs + 2);  // fills only past the last frame's length
  copy_short(f.raw.data(), b.data(), cs + 2);
  f.findings.clear();
  r = Verdict{ParseStatus::frame, cs + 2};
  return true;
}

Verdict not_a_header(Parse& p) {
  return invalid(p.err, FindingCode::bad_header, 1, p.text([&] {
    return cat({"'#' followed by ", printable(p.b[1]), ", not a TOP header (#TP #tp #tP #Tp)"});
  }));
}

// Topotek 12.2 documents "#PDP16TMP<22 chars><RR>": no 'tp', no control, a
// two-digit length.
std::optional<Verdict> read_tmp_header(Parse& p) {
  static constexpr std::string_view kTmp = "#PDP??TMP";
  const std::string_view b = p.b;
  for (std::size_t i = 1; i < kTmp.size(); ++i) {
    if (i >= p.n) return p.more(33);
    bool okc = kTmp[i] == '?' ? is_hex(b[i]) : b[i] == kTmp[i];
    if (!okc) return not_a_header(p);
  }
  p.lay.header = Header::tmp_quirk;
  p.lay.ident_at = 6;
  p.lay.data_at = 9;
  p.lay.declared =
      static_cast<std::size_t>(hex_value(b[4])) * 16 + static_cast<std::size_t>(hex_value(b[5]));
  p.lay.hex_length = false;
  return std::nullopt;
}

// '#' and the header's family (#TP #tp #tP #Tp, or the whole TMP form).
std::optional<Verdict> read_header(Parse& p) {
  const std::string_view b = p.b;
  if (p.n == 0) return p.at_end ? p.cut(0, 1) : need_more();
  if (b[0] != '#')
    return invalid(p.err, FindingCode::bad_header, 0, p.text([&] {
      return cat({"frame must start with '#', got ", printable(b[0])});
    }));
  if (p.n < 2) return p.more(12);
  if (b[1] == 'P') return read_tmp_header(p);
  if (b[1] != 'T' && b[1] != 't') return not_a_header(p);
  if (p.n < 3) return p.more(12);
  if (b[2] != 'P' && b[2] != 'p')
    return invalid(p.err, FindingCode::bad_header, 2, p.text([&] {
      return cat({"\"#", b.substr(1, 1), "\" followed by ", printable(b[2]), ", not a TOP header"});
    }));
  if (b[1] == 'T')
    p.lay.header = b[2] == 'P' ? Header::fixed : Header::ext16;
  else
    p.lay.header = b[2] == 'p' ? Header::variable : Header::ext8;
  return std::nullopt;
}

std::optional<Verdict> read_addresses(Parse& p) {
  for (std::size_t i = 3; i < 5; ++i) {
    if (p.n < i + 1) return p.more(12);
    if (!is_address(p.b[i]))
      return invalid(p.err, FindingCode::bad_address, i, p.text([&] {
        return cat({i == 3 ? "source" : "destination", " address ", printable(p.b[i]),
                    " is not one of U M D E P G"});
      }));
  }
  return std::nullopt;
}

Verdict bad_control(Parse& p) {
  return invalid(p.err, FindingCode::bad_control, 6, p.text([&] {
    return cat({"control char ", printable(p.b[6]), " is not r or w"});
  }));
}

// A #TP/#tp length: one hex digit and the control char, or two hex digits
// (the TMP firmware quirk) and the control char.
std::optional<Verdict> read_hex_length(Parse& p) {
  const std::string_view b = p.b;
  Layout& lay = p.lay;
  if (!is_hex(b[5]))
    return invalid(p.err, FindingCode::bad_length_char, 5, p.text([&] {
      return cat({"length char ", printable(b[5]), " is not a hex digit"});
    }));
  if (is_lower_hex(b[5]))
    p.f.findings.push_back(make_finding(FindingCode::lowercase_hex, 5,
                                        p.text([] { return "length char written in lowercase"; })));
  if (p.n < 7) return p.more(12);
  if (b[6] == 'r' || b[6] == 'w') {
    lay.control = b[6];
    lay.declared = static_cast<std::size_t>(hex_value(b[5]));
  } else if (is_hex(b[6])) {
    // Two-digit length ("#tpDP16wTMP..."): the TMP firmware quirk.
    if (p.n < 8) return p.more(13);
    if (b[7] != 'r' && b[7] != 'w') return bad_control(p);
    lay.control = b[7];
    lay.declared =
        static_cast<std::size_t>(hex_value(b[5])) * 16 + static_cast<std::size_t>(hex_value(b[6]));
    lay.two_digit = true;
    lay.hex_length = false;
    lay.ident_at = 8;
    lay.data_at = 11;
  } else {
    return bad_control(p);
  }
  return std::nullopt;
}

// The length field and the control char, as the header encodes them.
std::optional<Verdict> read_length(Parse& p) {
  const std::string_view b = p.b;
  Layout& lay = p.lay;
  if (p.n < 6) return p.more(12);
  switch (lay.header) {
    case Header::fixed:
    case Header::variable:
      return read_hex_length(p);
    case Header::ext8:
      lay.declared = static_cast<unsigned char>(b[5]);
      lay.hex_length = false;
      if (p.n < 7) return p.more(12);
      if (b[6] != 'r' && b[6] != 'w') return bad_control(p);
      lay.control = b[6];
      break;
    case Header::ext16:
      if (p.n < 7) return p.more(12);
      lay.declared = static_cast<std::size_t>(static_cast<unsigned char>(b[5]) << 8 |
                                              static_cast<unsigned char>(b[6]));
      lay.hex_length = false;
      lay.control = 0;
      lay.ident_at = 7;
      lay.data_at = 10;
      break;
    case Header::tmp_quirk:
      break;
  }
  return std::nullopt;
}

// The identifier, and the declared length against the limit.
std::optional<Verdict> read_ident(Parse& p) {
  const Layout& lay = p.lay;
  for (std::size_t i = lay.ident_at; i < lay.ident_at + 3; ++i) {
    if (p.n < i + 1) return p.more(lay.data_at + 2);
    if (!is_ident_char(p.b[i]))
      return invalid(p.err, FindingCode::bad_ident, i, p.text([&] {
        return cat({"identifier char ", printable(p.b[i]), " is not an uppercase letter or digit"});
      }));
  }
  if (lay.declared > p.opts.max_data_length)
    return invalid(p.err, FindingCode::frame_too_long, 5, p.text([&] {
      return cat({"declared data length ", std::to_string(lay.declared), " exceeds the limit of ",
                  std::to_string(p.opts.max_data_length)});
    }));
  return std::nullopt;
}

// The frame's fields up to its data, as read.
void set_fields(Parse& p) {
  const std::string_view b = p.b;
  const Layout& lay = p.lay;
  Frame& f = p.f;
  f.src = lay.header == Header::tmp_quirk ? b[2] : b[3];
  f.dst = lay.header == Header::tmp_quirk ? b[3] : b[4];
  f.control = lay.control;
  f.ident[0] = b[lay.ident_at];
  f.ident[1] = b[lay.ident_at + 1];
  f.ident[2] = b[lay.ident_at + 2];
  f.declared_length = static_cast<std::uint32_t>(lay.declared);
  f.data_offset = static_cast<std::uint32_t>(lay.data_at);
}

// The TMP quirk (the documented form, or a TMP frame with a two-digit
// length), or a two-digit length on another identifier.
void note_length_form(Parse& p) {
  const Layout& lay = p.lay;
  const bool tmp_form = lay.header == Header::tmp_quirk;
  if (tmp_form || (lay.two_digit && p.f.ident_view() == "TMP")) {
    p.f.findings.push_back(make_finding(FindingCode::tmp_quirk, tmp_form ? 1 : 5, p.text([&] {
      return tmp_form ? "the malformed TMP form documented in Topotek 12.2 "
                        "(#PDP16TMP: no 'tp', two-digit length, no control char)"
                      : "TMP frame with a two-digit length (Topotek 12.2: 22 data "
                        "chars do not fit one hex digit)";
    }),
                                        quirk_id(FindingCode::tmp_quirk)));
  } else if (lay.two_digit) {
    p.f.findings.push_back(make_finding(FindingCode::two_digit_length, 5, p.text([&] {
      return cat({"length written as two hex digits (0x", p.b.substr(5, 2), ")"});
    })));
  }
}

// The general parser (parse_frame tries parse_plain first). A frame is
// built in `f` (reset first), which the result refers to only when its
// status is frame.
Verdict parse_into(std::string_view b, bool at_end, const ParseOptions& opts, Frame& f,
                   Finding& err) {
  reset_frame(f);
  Parse p{b, at_end, opts, f, err, b.size(), Layout{}};
  if (auto r = read_header(p)) return *r;
  f.header = p.lay.header;
  if (p.lay.header != Header::tmp_quirk) {
    if (auto r = read_addresses(p)) return *r;
    if (auto r = read_length(p)) return *r;
  }
  if (auto r = read_ident(p)) return *r;
  set_fields(p);
  note_length_form(p);
  return judge_checksum(p);
}

}  // namespace

}  // namespace detail

ParseResult parse_frame(std::string_view bytes, bool at_end, const ParseOptions& opts) {
  ParseResult r;
  parse_frame(bytes, at_end, opts, r);
  return r;
}

void parse_frame(std::string_view bytes, bool at_end, const ParseOptions& opts, ParseResult& out) {
  // the common frame here, without parse_into's entry (it saves the
  // registers of the whole general parse)
  if (detail::Verdict plain; detail::parse_plain(bytes, opts, out.frame, plain)) {
    // the error of an earlier parse goes (most parses have none to write)
    if (out.error.code != FindingCode{} || !out.error.message.empty()) out.error = Finding{};
    out.status = plain.status;
    out.consumed = plain.consumed;
    return;
  }
  detail::parse_frame_general(bytes, at_end, opts, out);
}

void detail::parse_frame_general(std::string_view bytes, bool at_end, const ParseOptions& opts,
                                 ParseResult& out) {
  if (out.error.code != FindingCode{} || !out.error.message.empty()) out.error = Finding{};
  const detail::Verdict r = detail::parse_into(bytes, at_end, opts, out.frame, out.error);
  out.status = r.status;
  out.consumed = r.consumed;
  if (r.status != ParseStatus::frame) detail::reset_frame(out.frame);
}

void parse_exact(std::string_view bytes, const ParseOptions& opts, ParseResult& r) {
  parse_frame(bytes, true, opts, r);
  if (r.status != ParseStatus::frame) return;
  std::size_t i = r.consumed;
  std::size_t crlf = 0;
  while (i < bytes.size() && (bytes[i] == '\r' || bytes[i] == '\n')) {
    ++i;
    ++crlf;
  }
  if (crlf > 0) {
    r.frame.terminator = static_cast<std::uint8_t>(std::min(crlf, kMaxTerminator));
    r.frame.findings.push_back(
        make_finding(FindingCode::crlf, static_cast<std::uint32_t>(r.consumed),
                     cat({"frame followed by ", std::to_string(crlf), " CR/LF byte(s)"})));
  }
  if (i < bytes.size())
    r.frame.findings.push_back(
        make_finding(FindingCode::trailing_bytes, static_cast<std::uint32_t>(i),
                     cat({std::to_string(bytes.size() - i), " byte(s) after the frame"})));
  r.consumed = bytes.size();
}

ParseResult parse_exact(std::string_view bytes, const ParseOptions& opts) {
  ParseResult r;
  parse_exact(bytes, opts, r);
  return r;
}

}  // namespace top
