// The second half of the general frame parse: with the header, length and
// identifier read (frame_parse.cpp), where the data ends and what the
// checksum says: right, lowercase, right for another data length (a lying
// length), missing, right under another header case, or wrong.
#include <array>
#include <cstdint>
#include <optional>

#include "frame_parse.hpp"
#include "top/device.hpp"

namespace top::detail {

namespace {

// Header variants whose checksum a sender may have used by mistake.
constexpr std::array<std::array<char, 2>, 4> kHeaderVariants = {
    {{'T', 'P'}, {'t', 'p'}, {'t', 'P'}, {'T', 'p'}}};

// The frame ends after data_len bytes of data and, when present, the two
// checksum digits (value `value`; prefix: the sum of the bytes before them).
Verdict finish(Parse& p, std::size_t data_len, bool present, std::uint8_t value, unsigned prefix) {
  Frame& f = p.f;
  Verdict r{ParseStatus::frame, 0};
  f.data_length = static_cast<std::uint32_t>(data_len);
  std::size_t end = p.lay.data_at + data_len + (present ? 2 : 0);
  f.raw.append(p.b.data(), end);  // empty since the reset (cheaper than assign)
  f.expected_checksum = static_cast<std::uint8_t>(prefix & 0xFF);
  f.checksum_present = present;
  f.checksum = value;
  f.checksum_ok = present && value == f.expected_checksum;
  r.consumed = end;
  return r;
}

// The checksum at the declared boundary (at `cs`; `prefix` the sum before
// it) validates: the frame, with a finding when its digits are lowercase.
std::optional<Verdict> declared_checksum(Parse& p, std::size_t cs, unsigned prefix) {
  const std::string_view b = p.b;
  std::uint8_t v = 0;
  if (!checksum_at(b, cs, prefix, v)) return std::nullopt;
  if (is_lower_hex(b[cs]) || is_lower_hex(b[cs + 1]))
    p.f.findings.push_back(
        make_finding(FindingCode::checksum_case, static_cast<std::uint32_t>(cs), p.text([&] {
          return cat({"checksum ", b.substr(cs, 2),
                      " is right but lowercase; strict receivers expect ", hex2(v)});
        })));
  Verdict r = finish(p, p.lay.declared, true, v, prefix);
  if (take_second_checksum(p.f, b.substr(cs + 2), p.at_end, p.opts.messages) == SecondChecksum::yes)
    r.consumed += 2;
  return r;
}

// The declared length fails: the one other one-digit data length whose
// checksum validates and is followed by a boundary, if exactly one does.
std::optional<Verdict> recover_length(Parse& p) {
  const std::string_view b = p.b;
  const std::size_t n = p.n, L = p.lay.declared, data_at = p.lay.data_at;
  // Look-ahead needed to judge other data lengths: every one-digit length
  // plus its checksum and the byte after it.
  const std::size_t lookahead = data_at + max_data_hex + 3;
  if (!p.at_end && n < lookahead) return need_more(lookahead);
  std::size_t found = SIZE_MAX;
  int count = 0;
  std::uint8_t found_value = 0;
  unsigned found_prefix = 0;
  unsigned s = byte_sum(b.data(), data_at);
  for (std::size_t dl = 0; dl <= max_data_hex; ++dl) {
    std::size_t at = data_at + dl;
    if (dl > 0) s += static_cast<unsigned char>(b[at - 1]);
    if (at + 2 > n) break;
    if (dl == L) continue;
    std::uint8_t v = 0;
    if (!checksum_at(b, at, s, v)) continue;
    bool bounded = (at + 2 == n && p.at_end) || (at + 2 < n && is_boundary(b[at + 2]));
    if (!bounded) continue;
    ++count;
    found = dl;
    found_value = v;
    found_prefix = s;
  }
  if (count != 1) return std::nullopt;
  // A length that counts bytes, in a form real devices are recorded with.
  if (found == 2 * L && L > 0)
    if (const DeviceForm* rf = length_in_bytes_form(p.f)) {
      p.f.findings.push_back(make_finding(FindingCode::length_in_bytes, 5, p.text([&] {
        return cat({"length ", std::to_string(L), " counts the bytes of ", std::to_string(found),
                    " hex data chars, as recorded: ", rf->evidence});
      }),
                                          quirk_id(FindingCode::length_in_bytes)));
      return finish(p, found, true, found_value, found_prefix);
    }
  p.f.findings.push_back(make_finding(FindingCode::length_mismatch, 5, p.text([&] {
    return cat({"declared length ", std::to_string(L), " but the checksum validates with ",
                std::to_string(found), " data bytes; decoded with ", std::to_string(found)});
  })));
  return finish(p, found, true, found_value, found_prefix);
}

// The frame stops where its checksum should start (at `cs`; `prefix` the
// sum before it).
Verdict no_checksum(Parse& p, std::size_t cs, unsigned prefix) {
  p.f.findings.push_back(
      make_finding(FindingCode::no_checksum, static_cast<std::uint32_t>(cs), p.text([&] {
        return cat({"frame ends where its checksum should be (expected ",
                    hex2(static_cast<std::uint8_t>(prefix)), ")"});
      })));
  return finish(p, p.lay.declared, false, 0, prefix);
}

// Two checksum bytes at `cs` that do not validate: say whether they are the
// sum under another header case, else a bad checksum.
Verdict wrong_checksum(Parse& p, std::size_t cs, unsigned prefix) {
  const std::string_view b = p.b;
  std::uint8_t expected = static_cast<std::uint8_t>(prefix & 0xFF);
  const std::string_view got = b.substr(cs, 2);
  int hi = hex_value(b[cs]), lo = hex_value(b[cs + 1]);
  bool present = hi >= 0 && lo >= 0;
  std::uint8_t value = present ? static_cast<std::uint8_t>(hi * 16 + lo) : 0;
  if (present && p.lay.header != Header::tmp_quirk) {
    unsigned base = prefix - static_cast<unsigned char>(b[1]) - static_cast<unsigned char>(b[2]);
    for (const auto& v : kHeaderVariants) {
      if (v[0] == b[1] && v[1] == b[2]) continue;
      unsigned alt = base + static_cast<unsigned char>(v[0]) + static_cast<unsigned char>(v[1]);
      if (static_cast<std::uint8_t>(alt & 0xFF) == value) {
        p.f.findings.push_back(make_finding(FindingCode::checksum_header_case,
                                            static_cast<std::uint32_t>(cs), p.text([&] {
                                              return cat({"checksum ",
                                                          got,
                                                          " is the sum with header #",
                                                          {v.data(), 2},
                                                          ", not #",
                                                          b.substr(1, 2),
                                                          " (expected ",
                                                          hex2(expected),
                                                          ")"});
                                            }),
                                            quirk_id(FindingCode::checksum_header_case)));
        return finish(p, p.lay.declared, true, value, prefix);
      }
    }
  }
  p.f.findings.push_back(
      make_finding(FindingCode::bad_checksum, static_cast<std::uint32_t>(cs),
                   present ? p.text([&] {
                     return cat({"checksum ", got, ", expected ", hex2(expected)});
                   })
                           : p.text([&] {
                               return cat({"checksum field '", got,
                                           "' is not two hex digits, expected ", hex2(expected)});
                             })));
  return finish(p, p.lay.declared, present, value, prefix);
}

}  // namespace

SecondChecksum take_second_checksum(Frame& f, std::string_view rest, bool at_end, bool messages) {
  // Only after a checksum that validates at the declared boundary, once.
  const std::size_t end = f.raw.size();
  if (!f.checksum_ok || f.data_length != f.declared_length || f.terminator != 0 ||
      end != std::size_t{f.data_offset} + f.data_length + 2 || f.has(FindingCode::double_checksum))
    return SecondChecksum::no;
  const auto sum =
      static_cast<std::uint8_t>(f.expected_checksum + static_cast<unsigned char>(f.raw[end - 2]) +
                                static_cast<unsigned char>(f.raw[end - 1]));
  const int want[2] = {sum >> 4, sum & 0xF};
  for (std::size_t i = 0; i < 2; ++i) {
    if (i >= rest.size()) return at_end ? SecondChecksum::no : SecondChecksum::undecided;
    if (hex_value(rest[i]) != want[i]) return SecondChecksum::no;
  }
  if (rest.size() == 2 && !at_end) return SecondChecksum::undecided;
  if (rest.size() > 2 && !is_boundary(rest[2])) return SecondChecksum::no;
  f.findings.push_back(make_finding(FindingCode::double_checksum, static_cast<std::uint32_t>(end),
                                    messages ? cat({"a second checksum ", rest.substr(0, 2),
                                                    " over the frame and its checksum follows it"})
                                             : std::string(),
                                    quirk_id(FindingCode::double_checksum)));
  // The frame's bytes are all it consumed, the second checksum too.
  f.raw.append(rest.data(), 2);
  return SecondChecksum::yes;
}

Verdict judge_checksum(Parse& p) {
  const std::size_t n = p.n;
  const std::size_t declared_cs = p.lay.data_at + p.lay.declared;
  const std::size_t declared_end = declared_cs + 2;

  // Every byte before the data is read: nothing changes until the checksum.
  if (!p.at_end && n < declared_end) return need_more(declared_end);

  unsigned prefix_declared = 0;
  if (n >= declared_end) {
    prefix_declared = byte_sum(p.b.data(), declared_cs);
    if (auto r = declared_checksum(p, declared_cs, prefix_declared)) return *r;
  }

  // The declared boundary does not validate.
  if (p.lay.hex_length && p.opts.recover_lying_length)
    if (auto r = recover_length(p)) return *r;

  if (n < declared_end) {
    // Only reachable at the end of input.
    if (n == declared_cs) return no_checksum(p, declared_cs, byte_sum(p.b.data(), declared_cs));
    return p.cut(n, declared_end);
  }

  // No checksum at all: the data is followed directly by a boundary.
  if (is_boundary(p.b[declared_cs])) return no_checksum(p, declared_cs, prefix_declared);
  return wrong_checksum(p, declared_cs, prefix_declared);
}

}  // namespace top::detail
