// Target: the fast parser (protocol/) against the reference parser written
// from the documents (reference.hpp). They must agree on this domain:
//
// 1. Verdict on the whole input as one frame: the reference accepts it as
//    exactly one frame iff parse_exact returns a frame of every input byte
//    with a valid checksum and no finding at all. When both accept, header,
//    addresses, control, identifier, declared length, data offset, data and
//    checksum value are equal.
// 2. Frame boundaries on a stream: when the reference splits the whole input
//    into back-to-back frames, the stream decoder yields exactly those frames
//    (offsets and lengths) and nothing else; and when the stream decoder
//    yields only clean frames that cover the input, the reference splits it
//    the same way.
// 3. Decoded fields: for each frame of case 1 and each dialect where both the
//    reference (from the text of the documents) and the catalog have a layout
//    for its identifier, control and length, the fields have the same count,
//    the same validity and the same raw integer values.
// Any disagreement aborts.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "check.hpp"
#include "mutator.hpp"
#include "reference.hpp"
#include "reuse.hpp"
#include "top/top.hpp"

using topfuzz::show;

namespace {

bool clean(const top::Frame& f) { return f.checksum_ok && f.findings.empty(); }

void compare_fields(const top::Frame& f, const topref::Frame& g, std::string_view in) {
  static constexpr struct {
    top::Dialect d;
    const char* name;
  } kDialects[] = {{top::Dialect::skydroid, "skydroid"}, {top::Dialect::topotek, "topotek"}};
  for (const auto& [d, name] : kDialects) {
    const topref::Layout* layout = topref::find_layout(name, g);
    if (layout == nullptr) continue;
    top::DecodeOptions o;
    o.dialect = d;
    static top::Decoded dec = topfuzz::reused_decoded();
    const topfuzz::ReleaseAtEnd release(dec);
    top::decode(f, o, dec);
    if (dec.form == nullptr) continue;  // the catalog has no layout for it (yet)
    const std::vector<topref::Value> ref = topref::decode(*layout, g.data);
    FUZZ_CHECK(dec.fields.size() == ref.size(),
               std::string(name) + " \"" + show(in) + "\": catalog decodes " +
                   std::to_string(dec.fields.size()) + " fields, the document " +
                   std::to_string(ref.size()));
    for (std::size_t i = 0; i < ref.size(); ++i) {
      const top::FieldValue& v = dec.fields[i];
      FUZZ_CHECK(v.length == static_cast<std::uint32_t>(layout->fields[i].width),
                 std::string(name) + " \"" + show(in) + "\": field " + std::string(v.name()) +
                     " is " + std::to_string(v.length) + " chars wide, the document says " +
                     std::to_string(layout->fields[i].width));
      FUZZ_CHECK(v.valid == ref[i].valid && v.none == ref[i].none,
                 std::string(name) + " \"" + show(in) + "\": field " + std::string(v.name()) +
                     (v.none != ref[i].none ? " placeholder" : " validity") + " differs");
      if (v.valid && !v.none)
        FUZZ_CHECK(v.integer == ref[i].value,
                   std::string(name) + " \"" + show(in) + "\": field " + std::string(v.name()) +
                       " = " + std::to_string(v.integer) + ", the document gives " +
                       std::to_string(ref[i].value));
    }
  }
}

void single_frame(std::string_view in, const std::optional<topref::Frame>& g) {
  const bool ref_ok = g.has_value() && g->size == in.size();
  static top::ParseResult r = topfuzz::reused_parse_result();
  const topfuzz::ReleaseAtEnd release(r);
  static const top::ParseOptions quiet = [] {  // the parts are compared, not the texts
    top::ParseOptions o;
    o.messages = false;
    return o;
  }();
  top::parse_exact(in, quiet, r);
  const bool fast_ok = r.status == top::ParseStatus::frame && r.consumed == in.size() &&
                       r.frame.raw.size() == in.size() && clean(r.frame);
  FUZZ_CHECK(ref_ok == fast_ok, "\"" + show(in) + "\": the reference " +
                                    (ref_ok ? "accepts" : "rejects") + " it, the parser " +
                                    (fast_ok ? "accepts" : "rejects") + " it");
  if (!ref_ok) return;
  const top::Frame& f = r.frame;
  FUZZ_CHECK(f.header_text().substr(1) == g->header && f.src == g->src && f.dst == g->dst &&
                 f.control == g->control && f.ident_view() == g->ident &&
                 f.declared_length == g->length && f.data_length == g->length &&
                 f.data_offset == g->data_offset && f.data() == g->data &&
                 f.checksum == g->checksum,
             "\"" + show(in) + "\": the parts differ from the reference's");
  compare_fields(f, *g, in);
}

// `first`: the reference's parse at byte 0 (single_frame's).
void stream(std::string_view in, const std::optional<topref::Frame>& first) {
  // Kept across inputs (reuse.hpp): the decoder is reset, the lists cleared.
  static std::vector<std::pair<std::size_t, std::size_t>> ref, fast;
  static top::StreamDecoder d([] {  // boundaries only: no texts
    top::StreamOptions o;
    o.parse.messages = false;
    return o;
  }());
  static top::StreamItem it;
  const topfuzz::ReleaseAtEnd release(it);
  if (ref.capacity() == 0) {  // a frame or garbage item per byte at most
    ref.reserve(topfuzz::capped(std::size_t{1} << 16));
    fast.reserve(topfuzz::capped(std::size_t{1} << 16));
  }
  ref.clear();
  fast.clear();
  d.reset();
  std::size_t at = 0;
  if (first) {
    ref.emplace_back(0, first->size);
    at = first->size;
    while (at < in.size()) {
      const std::optional<topref::Frame> g = topref::parse(in.substr(at));
      if (!g) break;
      ref.emplace_back(at, g->size);
      at += g->size;
    }
  }
  const bool ref_split = !ref.empty() && at == in.size();

  // Items until the first that is not a clean frame: it decides that the
  // decoder does not split the input, and the decoder decodes no further
  // (one item at a time, as next() asks).
  d.feed(in);
  d.finish();
  bool fast_clean = true;
  while (d.next(it)) {
    if (it.kind != top::ItemKind::frame || !clean(it.frame) || it.frame.terminator != 0) {
      fast_clean = false;
      break;
    }
    fast.emplace_back(it.offset, it.length);
  }
  const bool fast_split = fast_clean && !fast.empty();
  FUZZ_CHECK(ref_split == fast_split,
             "\"" + show(in) + "\": the reference " + (ref_split ? "splits" : "does not split") +
                 " it into frames, the stream decoder " + (fast_split ? "does" : "does not"));
  if (ref_split)
    FUZZ_CHECK(ref == fast, "\"" + show(in) + "\": frame boundaries differ (" +
                                std::to_string(ref.size()) + " vs " + std::to_string(fast.size()) +
                                " frames)");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  size = topfuzz::capped(size);
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const std::optional<topref::Frame> first = topref::parse(in);  // both halves need it
  single_frame(in, first);
  stream(in, first);
  return 0;
}
