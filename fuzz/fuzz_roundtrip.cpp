// Target: the build/parse round trip, both ways.
//
// (a) Any input that parse_exact accepts as a clean frame (checksum right, no
//     finding at all, or only an all-lowercase checksum) and that is not the
//     TMP quirk form is rebuilt by build_frame from its parts byte for byte.
// (b) The input read as a frame description (byte 0: header and checksum
//     case, bytes 1-2: addresses, byte 3: control, bytes 4-6: identifier, the
//     rest: data) is built, and parse_exact gives back exactly those parts,
//     with a valid checksum and no finding.
#include <cstdint>
#include <string>
#include <string_view>

#include "check.hpp"
#include "mutator.hpp"
#include "top/top.hpp"

using namespace top;
using topfuzz::show;

namespace {

bool ident_ok(std::string_view s) {
  for (char c : s)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))) return false;
  return s.size() == 3;
}

void parse_then_build(std::string_view in) {
  const ParseResult r = parse_exact(in);
  if (r.status != ParseStatus::frame) return;
  const Frame& f = r.frame;
  if (!f.checksum_ok || f.header == Header::tmp_quirk) return;
  bool lower = false;
  for (const Finding& x : f.findings) {
    if (x.code != FindingCode::checksum_case) return;
    lower = true;
  }
  if (lower)
    for (char c : f.checksum_text())
      if (c >= 'A' && c <= 'F') return;  // mixed case cannot be rebuilt
  BuildSpec spec;
  spec.header = f.header;
  spec.src = f.src;
  spec.dst = f.dst;
  spec.control = f.control;
  spec.ident = f.ident_view();
  spec.data = f.data();
  spec.lowercase_checksum = lower;
  const std::string rebuilt = build_frame(spec);
  FUZZ_CHECK(rebuilt == f.raw, "parsed \"" + show(f.raw) + "\", rebuilt \"" + show(rebuilt) + "\"");
}

void build_then_parse(std::string_view in) {
  if (in.size() < 7) return;
  static constexpr char kAddr[] = "UMDEPG";
  static constexpr Header kHeaders[] = {Header::fixed, Header::variable, Header::ext8,
                                        Header::ext16};
  const auto b0 = static_cast<unsigned char>(in[0]);
  BuildSpec spec;
  spec.header = kHeaders[b0 & 3u];
  spec.lowercase_checksum = (b0 & 4u) != 0;
  spec.src = kAddr[static_cast<unsigned char>(in[1]) % 6];
  spec.dst = kAddr[static_cast<unsigned char>(in[2]) % 6];
  spec.control = (static_cast<unsigned char>(in[3]) & 1u) ? 'w' : 'r';
  spec.ident = in.substr(4, 3);
  spec.data = in.substr(7);
  if (!ident_ok(spec.ident)) return;

  Header expect = spec.header;
  if ((expect == Header::fixed || expect == Header::variable) && spec.data.size() > max_data_hex)
    expect = Header::ext8;
  if (expect == Header::ext8 && spec.data.size() > max_data_ext8) expect = Header::ext16;

  const std::string raw = build_frame(spec);
  const ParseResult r = parse_exact(raw);
  FUZZ_CHECK(r.status == ParseStatus::frame, "built \"" + show(raw) + "\" does not parse");
  const Frame& f = r.frame;
  const bool has_letter = raw[raw.size() - 2] > '9' || raw[raw.size() - 1] > '9';
  const std::size_t allowed = spec.lowercase_checksum && has_letter ? 1 : 0;
  FUZZ_CHECK(f.checksum_ok && f.findings.size() == allowed &&
                 (allowed == 0 || f.findings[0].code == FindingCode::checksum_case),
             "built \"" + show(raw) + "\" parses with findings or a bad checksum");
  FUZZ_CHECK(f.header == expect && f.src == spec.src && f.dst == spec.dst &&
                 f.control == (expect == Header::ext16 ? 0 : spec.control) &&
                 f.ident_view() == spec.ident && f.data() == spec.data &&
                 f.declared_length == spec.data.size() && f.raw == raw && r.consumed == raw.size(),
             "built \"" + show(raw) + "\" parses to other parts");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  size = topfuzz::capped(size);
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  parse_then_build(in);
  build_then_parse(in);
  return 0;
}
