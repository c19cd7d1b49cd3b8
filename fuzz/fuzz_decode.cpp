// Target: catalog decoding of one dialect (TOPKIT_FUZZ_DIALECT: 1 skydroid,
// 2 topotek), built as fuzz_decode_skydroid and fuzz_decode_topotek.
//
// Input: byte 0 picks the model, the role and the client address; byte 1 a
// command of the dialect's table; byte 2 one of its forms; the rest is the
// data. The harness builds the frame (the header the dialect would use),
// so the fuzzer spends its time in the field decoders, not in framing.
// Checks: the built frame parses back to the same parts; decode() finds the
// command; fields lie inside the data, in order; and a form decoded cleanly
// from numeric fields encodes back to the same data (encode_fields).
#include <cctype>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "check.hpp"
#include "reuse.hpp"
#include "top/detail/decode_cache.hpp"
#include "top/detail/prefilter.hpp"
#include "top/top.hpp"

using namespace top;
using topfuzz::show;

#ifndef TOPKIT_FUZZ_DIALECT
#error "define TOPKIT_FUZZ_DIALECT (1 skydroid, 2 topotek)"
#endif

namespace {

constexpr Dialect kDialect = static_cast<Dialect>(TOPKIT_FUZZ_DIALECT);

bool encodable(FieldKind k) { return is_integer_kind(k) || k == FieldKind::enum_hex; }

// The decoded values of a cleanly decoded numeric form, encoded again, give
// the data back (uppercase hex, as encode_fields writes it).
void check_reencode(const FormSpec& form, const Decoded& d, std::string_view data) {
  if (d.fields.size() != form.fields.size()) return;
  std::size_t total = 0;
  for (const FieldValue& v : d.fields) {
    if (!v.valid || v.none || !encodable(v.spec->kind) || v.spec->width == 0) return;
    total += v.length;
  }
  if (total != data.size()) return;
  for (char c : data)
    if (c >= 'a' && c <= 'f') return;  // lowercase hex is reported, not re-encoded
  std::vector<EncodeValue> values(d.fields.size());
  for (std::size_t i = 0; i < d.fields.size(); ++i) values[i].number = d.fields[i].value;
  std::string out;
  FUZZ_CHECK(encode_fields(form, values, out),
             "encode_fields refused values it decoded from \"" + show(data) + "\"");
  FUZZ_CHECK(out == data, "decoded \"" + show(data) + "\", encoded back \"" + show(out) + "\"");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  size = topfuzz::capped(size);
  const std::span<const CommandSpec> table = commands(kDialect);
  if (size < 3 || table.empty()) return 0;
  const CommandSpec& cmd = table[bytes[1] % table.size()];
  if (cmd.forms.empty()) return 0;
  const FormSpec& form = cmd.forms[bytes[2] % cmd.forms.size()];
  const std::string_view data(reinterpret_cast<const char*>(bytes + 3), size - 3);

  // Byte 0: bits 0-2 model (0 = unknown, else the n-th model of the dialect),
  // bits 3-4 role, bit 5 client address P instead of U.
  static const std::vector<Model> models = [] {
    std::vector<Model> v{Model::unknown};
    for (Model m : all_models())
      if (dialect_of(m) == kDialect) v.push_back(m);
    return v;
  }();
  DecodeOptions opts;
  opts.dialect = kDialect;
  opts.model = models[(bytes[0] & 7u) % models.size()];
  static constexpr Role kRoles[] = {Role::any, Role::request, Role::response, Role::any};
  opts.role = kRoles[(bytes[0] >> 3) & 3u];
  const char client = (bytes[0] & 0x20) ? 'P' : 'U';
  const bool response = form.role == Role::response;

  BuildSpec spec;
  spec.header = choose_header(kDialect, cmd.address, data.size());
  spec.src = response ? cmd.address : client;
  spec.dst = response ? client : cmd.address;
  spec.control = form.control;
  spec.ident = cmd.ident;
  spec.data = data;
  // Kept across inputs (reuse.hpp).
  static std::string raw = topfuzz::reused_text();
  build_frame(spec, raw);

  static ParseResult r = topfuzz::reused_parse_result();
  static Decoded d = topfuzz::reused_decoded(), v = topfuzz::reused_decoded(),
                 c = topfuzz::reused_decoded();
  const topfuzz::ReleaseAtEnd release(r, d, v, c);
  parse_exact(raw, ParseOptions{}, r);
  FUZZ_CHECK(r.status == ParseStatus::frame && r.frame.checksum_ok,
             "a built frame does not parse: \"" + show(raw) + "\"");
  const Frame& f = r.frame;
  FUZZ_CHECK(f.data() == data && f.ident_view() == cmd.ident,
             "a built frame parses to other parts: \"" + show(raw) + "\"");

  decode(f, opts, d);
  FUZZ_CHECK(d.dialect == kDialect, "decoded in another dialect");
  FUZZ_CHECK(d.command != nullptr && d.command->ident == cmd.ident,
             "decode() did not find " + std::string(cmd.ident));
  static std::string text = topfuzz::reused_text();
  std::uint32_t next = f.data_offset;
  for (const FieldValue& fv : d.fields) {
    FUZZ_CHECK(fv.spec != nullptr && fv.offset == next,
               "field " + std::string(fv.name()) + " does not follow the previous one");
    next = fv.offset + fv.length;
    FUZZ_CHECK(next <= f.data_offset + f.data_length, "field past the data");
    text.clear();
    append_value(fv, text);  // format_value() without a string per field
  }
  text.clear();
  d.append_summary(text);  // summary() without a string per input
  FUZZ_CHECK(text.empty() == d.fields.empty(), "a summary must exist exactly when fields do");
  if (d.form != nullptr) check_reencode(*d.form, d, data);

  // Without detail (topdump stats) the verdict is the same: command, form,
  // role, and every finding's code, severity and offset.
  DecodeOptions bare = opts;
  bare.detail = false;
  decode(f, bare, v);
  bool same = v.dialect == d.dialect && v.role == d.role && v.command == d.command &&
              v.form == d.form && v.motion == d.motion && v.switches == d.switches &&
              v.fields.empty() && v.findings.size() == d.findings.size();
  for (std::size_t i = 0; same && i < v.findings.size(); ++i)
    same = v.findings[i].code == d.findings[i].code &&
           v.findings[i].severity == d.findings[i].severity &&
           v.findings[i].offset == d.findings[i].offset;
  FUZZ_CHECK(same, "decoding without detail changes the verdict on \"" + show(raw) + "\"");

  // Through the shape cache (kept across inputs, so its slots hold other
  // shapes' results): the same verdict, quirks included, and the session's
  // prefilter as the identifier gives it.
  static detail::DecodeCache cache;
  const bool diagnosed = detail::decode(f, bare, &cache, c);
  same = c.dialect == v.dialect && c.role == v.role && c.command == v.command && c.form == v.form &&
         c.motion == v.motion && c.switches == v.switches &&
         diagnosed == detail::may_matter_to_diagnoses(f.ident) && c.fields.empty() &&
         c.findings.size() == v.findings.size();
  for (std::size_t i = 0; same && i < c.findings.size(); ++i)
    same = c.findings[i].code == v.findings[i].code &&
           c.findings[i].severity == v.findings[i].severity &&
           c.findings[i].offset == v.findings[i].offset &&
           c.findings[i].quirk == v.findings[i].quirk;
  FUZZ_CHECK(same, "the decode cache changes the verdict on \"" + show(raw) + "\"");
  return 0;
}
