#include "conf/fuzz_cases.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "top/detail/repair.hpp"
#include "top/device.hpp"
#include "top/enum_names.hpp"
#include "top/probe.hpp"

namespace topconf {
namespace {

using top::FieldKind;

std::uint64_t splitmix(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::string hex_digits(std::uint64_t v, std::size_t width) {
  std::string s(width, '0');
  for (std::size_t i = width; i-- > 0; v >>= 4) s[i] = "0123456789ABCDEF"[v & 0xF];
  return s;
}

// The raw text of one numeric field holding `raw` (an integer before the
// scale), or "" when the field cannot carry it at all.
std::string encode_raw(const top::FieldSpec& f, std::int64_t raw) {
  const std::size_t w = f.width;
  switch (f.kind) {
    case FieldKind::hex_u:
    case FieldKind::enum_hex:
      if (w == 0 || w > 15 || raw < 0 || raw >= (std::int64_t{1} << (4 * w))) return "";
      return hex_digits(static_cast<std::uint64_t>(raw), w);
    case FieldKind::hex_s: {
      if (w == 0 || w > 15) return "";
      const std::int64_t lim = std::int64_t{1} << (4 * w - 1);
      if (raw < -lim || raw >= lim) return "";
      return hex_digits(static_cast<std::uint64_t>(raw) & ((std::uint64_t{1} << (4 * w)) - 1), w);
    }
    case FieldKind::dec_u: {
      if (w == 0 || w > 18 || raw < 0) return "";
      std::string s = std::to_string(raw);
      if (s.size() > w) return "";
      return std::string(w - s.size(), '0') + s;
    }
    case FieldKind::le_i16:
    case FieldKind::le_u16:
    case FieldKind::le_i32: {
      const std::size_t n = f.kind == FieldKind::le_i32 ? 4 : 2;
      std::string s(n, '\0');
      for (std::size_t i = 0; i < n; ++i)
        s[i] = static_cast<char>((static_cast<std::uint64_t>(raw) >> (8 * i)) & 0xFF);
      return s;
    }
    case FieldKind::enum_char:
      if (w != 1 || raw < 0x20 || raw > 0x7E) return "";
      return std::string(1, static_cast<char>(raw));
    default:
      return "";
  }
}

constexpr std::string_view kPromise[] = {"none", "answer", "error", "silence"};
static_assert(std::size(kPromise) == static_cast<std::size_t>(Promise::silence) + 1);

const char* hex_byte(unsigned char c) {
  static char b[4];
  std::snprintf(b, sizeof b, "%02X", static_cast<unsigned>(c));
  return b;
}

}  // namespace

std::string_view to_string(Promise p) noexcept { return top::enum_name(kPromise, p); }

std::string mutate(std::string b, std::uint64_t s, bool repair) {
  static constexpr std::string_view kTokens[] = {"#",
                                                 "\r\n",
                                                 "#TP",
                                                 "#tp",
                                                 "#tP",
                                                 "#Tp",
                                                 "\n",
                                                 top::error_reply_ident,
                                                 top::error_reply_data,
                                                 "\xFF"};
  const int edits = 1 + static_cast<int>(splitmix(s) % 4);
  for (int e = 0; e < edits; ++e) {
    const std::uint64_t r = splitmix(s);
    const std::size_t at = b.empty() ? 0 : static_cast<std::size_t>(splitmix(s) % b.size());
    switch (r % 7) {
      case 0:
        if (!b.empty()) b[at] = static_cast<char>(b[at] ^ (1 << (splitmix(s) % 8)));
        break;
      case 1:
        if (!b.empty()) b[at] = static_cast<char>(splitmix(s) & 0xFF);
        break;
      case 2:
        b.insert(at, 1, static_cast<char>(splitmix(s) & 0xFF));
        break;
      case 3:
        if (!b.empty()) b.erase(at, 1 + splitmix(s) % std::min<std::size_t>(4, b.size() - at));
        break;
      case 4: {
        const std::size_t n = std::min<std::size_t>(b.size() - at, 1 + splitmix(s) % 16);
        if (b.size() < 4096) b.insert(at, b.substr(at, n));
        break;
      }
      case 5:
        b.insert(at, kTokens[splitmix(s) % std::size(kTokens)]);
        break;
      default:
        // Change a character in the frame's head (header, addresses,
        // length, control, identifier), where the parser decides most.
        if (b.size() > 10) {
          const std::size_t h = static_cast<std::size_t>(splitmix(s) % 10);
          static constexpr char kHead[] = "#TtPpUMDEGPrwXx0123456789ABCDEFZ";
          b[h] = kHead[splitmix(s) % (sizeof kHead - 1)];
        }
    }
  }
  if (repair && !b.empty())
    top::detail::repair_frames(reinterpret_cast<std::uint8_t*>(b.data()), b.size());
  return b;
}

namespace {

top::BuildSpec spec(top::Header h, char src, char dst, char ctl, std::string_view ident,
                    std::string_view data) {
  return {.header = h, .src = src, .dst = dst, .control = ctl, .ident = ident, .data = data};
}

std::string frame(top::Header h, char src, char dst, char ctl, std::string_view ident,
                  std::string_view data) {
  return top::build_frame(spec(h, src, dst, ctl, ident, data));
}

// The header of the other case: #TP and #tp, #tP and #Tp.
top::Header other_case(top::Header h) noexcept {
  switch (h) {
    case top::Header::fixed:
      return top::Header::variable;
    case top::Header::variable:
      return top::Header::fixed;
    case top::Header::ext8:
      return top::Header::ext16;
    case top::Header::ext16:
      return top::Header::ext8;
    default:
      return h;
  }
}

}  // namespace

CaseSource::CaseSource(top::Model model, char client, std::uint64_t seed, const Matrix* matrix)
    : model_(model),
      dialect_(top::dialect_of(model)),
      client_(client),
      seed_(seed),
      matrix_(matrix) {
  add_global();
  // Every identifier and form of the model.
  for (const top::CommandSpec& c : top::commands(dialect_)) {
    if (!c.supports(model_) || top::is_error_reply(c.ident)) continue;
    for (const top::FormSpec& form : c.forms)
      if (form.role != top::Role::response) add_form(c, form);
  }
}

// Global families first: short, and they reach the parser's corners.
void CaseSource::add_global() {
  const bool sky = dialect_ == top::Dialect::skydroid;
  // A read the device answers, for the framing and address cases: the
  // catalog's first liveness probe (top/probe.hpp: a read for every model).
  const auto probes = top::liveness_probes(model_);
  const top::LivenessProbe rd = probes.empty() ? top::LivenessProbe{} : probes[0];
  const std::string probe = frame(top::Header::fixed, client_, rd.address, 'r', rd.ident, rd.data);
  // What the oversized, binary and nested cases carry (a gimbal write), and
  // where the unknown identifiers go (the camera), on both dialects.
  const char gimbal = 'G', camera = 'D';
  const std::string_view carried = "GAY";

  add("oversized", "#tP 255 data bytes",
      frame(top::Header::ext8, client_, gimbal, 'w', carried, std::string(255, '0')));
  add("oversized", "#Tp 1000 data bytes",
      frame(top::Header::ext16, client_, gimbal, 'w', carried, std::string(1000, 'A')));
  add("oversized", "#Tp 4000 data bytes",
      frame(top::Header::ext16, client_, camera, 'r', "VER", std::string(4000, '7')));
  // Lengths that lie past what is carried, with a checksum of 00.
  {
    top::BuildSpec b{.header = top::Header::ext16,
                     .src = client_,
                     .dst = gimbal,
                     .ident = carried,
                     .declared_length = 0xFFFF,
                     .checksum = 0};
    const std::string ones(100, '1');
    b.data = ones;
    add("oversized", "#Tp declares 65535, carries 100", top::build_frame(b));
    b.header = top::Header::ext8;
    b.declared_length = 0xFF;
    b.data = std::string_view(ones).substr(0, 10);
    add("oversized", "#tP declares 255, carries 10", top::build_frame(b));
  }
  {
    const std::string zeros(40, '0');
    top::BuildSpec b{.header = top::Header::variable,
                     .src = client_,
                     .dst = gimbal,
                     .ident = carried,
                     .data = zeros,
                     .declared_length = 0xF,
                     .keep_header = true};
    add("oversized", "#tp data of 40 chars under a one-digit length", top::build_frame(b));
  }
  for (int c : {0x00, 0x01, 0x23, 0x7F, 0x80, 0xFF, 0x0D, 0x0A}) {
    std::string data = "\x10\x27";
    data += static_cast<char>(c);
    data += "#\x00\x23#";
    data.push_back('\0');
    data += static_cast<char>(c);
    add("binary",
        std::string("#tP binary data with '#' and ") + hex_byte(static_cast<unsigned char>(c)),
        frame(top::Header::ext8, client_, gimbal, 'w', sky ? carried : "GPS", data));
  }
  for (const char* id : {"ZZZ", "AAA", "999", "A0Z", "QQQ"})
    add("unknown-ident", std::string("unknown identifier ") + id,
        frame(top::Header::fixed, client_, camera, 'r', id, "00"));
  for (std::string_view id : {"gay", "G!Y", "G Y", "GA\x01"})
    add("unknown-ident", "bad identifier " + top::escape(id),
        frame(top::Header::fixed, client_, camera, 'r', id, "00"));
  for (char src : {'G', 'D', 'M', 'E', 'X', 'u', '#', '\0'})
    add("address", "source " + top::escape(std::string(1, src)),
        frame(top::Header::fixed, src, rd.address, 'r', rd.ident, rd.data));
  for (char dst : {'U', 'P', 'G', 'M', 'E', 'Z', 'g', '\x7F'})
    add("address", "destination " + top::escape(std::string(1, dst)),
        frame(top::Header::fixed, client_, dst, 'r', rd.ident, rd.data));
  add("address", "the other client address",
      frame(top::Header::fixed, client_ == 'U' ? 'P' : 'U', rd.address, 'r', rd.ident, rd.data));
  for (char ctl : {'R', 'W', 'x', '0', '\0', '\x1B', '#'})
    add("control", "control char " + top::escape(std::string(1, ctl)),
        frame(top::Header::fixed, client_, rd.address, ctl, rd.ident, rd.data));
  for (char c : {'\x00', '\x07', '\x1B', '\x7F'})
    add("control", "control char " + top::escape(std::string(1, c)) + " in the data",
        frame(top::Header::fixed, client_, rd.address, 'r', rd.ident, std::string(1, c) + "0"));
  add("framing", "lone #", "#");
  add("framing", "header only", "#TP");
  add("framing", "cut after the identifier", probe.substr(0, 10));
  add("framing", "empty line", "\r\n");
  add("framing", "CRLF after", probe + "\r\n");
  add("framing", "LF after", probe + "\n");
  add("framing", "CRLF before", "\r\n" + probe);
  add("framing", "garbage before", "\x01\xFFzz%" + probe);
  add("framing", "garbage after", probe + "xyz\x01");
  add("framing", "two frames", probe + probe);
  add("framing", "three frames with CRLF", probe + "\r\n" + probe + "\r\n" + probe + "\r\n");
  add("framing", "a frame inside another's data",
      frame(top::Header::ext8, client_, gimbal, 'w', carried, probe));
}

// The cases of one request form of a command.
void CaseSource::add_form(const top::CommandSpec& c, const top::FormSpec& form) {
  const std::string id(c.ident);
  const char ctl = form.control;
  std::string ex = top::example_data(form);
  if (top::stream_enabled_by(dialect_, id) && ctl == 'w') ex = "00";
  const std::string tag = id + " " + std::string(1, ctl) + " ";
  const top::Header h = top::choose_header(dialect_, c.address, ex.size());
  const top::BuildSpec valid_spec = spec(h, client_, c.address, ctl, id, ex);
  const std::string valid = top::build_frame(valid_spec);
  // The header written (the builder takes a larger one when the data needs it).
  const top::Header written = *top::header_from_string(std::string_view(valid).substr(0, 3));
  add("valid", tag + "example data", valid);
  add_values(c, form, h, tag, ex);
  // Wrong lengths.
  if (!ex.empty())
    add("length", tag + "one char short",
        frame(h, client_, c.address, ctl, id, ex.substr(0, ex.size() - 1)));
  add("length", tag + "one char long", frame(h, client_, c.address, ctl, id, ex + "0"));
  add("length", tag + "no data", frame(h, client_, c.address, ctl, id, ""));
  if (written == top::Header::variable && !ex.empty()) {
    // The length char lies; the checksum is right for the bytes sent.
    for (std::size_t n : {ex.size() - 1, ex.size() + 1}) {
      if (n > top::max_data_hex) continue;
      top::BuildSpec lie = valid_spec;
      lie.declared_length = static_cast<std::uint32_t>(n);
      add("length", tag + (n < ex.size() ? "length char one less" : "length char one more"),
          top::build_frame(lie));
    }
  }
  // The four headers, whatever the length.
  for (top::Header hh :
       {top::Header::fixed, top::Header::variable, top::Header::ext8, top::Header::ext16})
    if (hh != h && !(ex.size() > 15 && (hh == top::Header::fixed || hh == top::Header::variable)))
      add("header", tag + "under " + std::string(top::to_string(hh)),
          frame(hh, client_, c.address, ctl, id, ex));
  // Checksum variants.
  const std::string body = valid.substr(0, valid.size() - 2);
  top::BuildSpec wrong = valid_spec;
  wrong.checksum = static_cast<std::uint8_t>(top::checksum(body) + 1);
  add("checksum", tag + "wrong checksum", top::build_frame(wrong));
  top::BuildSpec lower = valid_spec;
  lower.lowercase_checksum = true;
  if (std::string f = top::build_frame(lower); f != valid)
    add("checksum", tag + "lowercase checksum", std::move(f));
  top::BuildSpec none = valid_spec;
  none.omit_checksum = true;
  add("checksum", tag + "no checksum", top::build_frame(none));
  top::BuildSpec other = valid_spec;
  other.checksum_header = other_case(written);
  add("checksum", tag + "checksum over the other header case", top::build_frame(other));
  // Framing around the command's own frame.
  add("framing", tag + "CRLF after", valid + "\r\n");
  add("framing", tag + "three copies", valid + valid + valid);
  add("framing", tag + "garbage before", "\x00\x7Fzz" + valid);
}

// Fields: boundaries, one step out, enum values and the one past.
void CaseSource::add_values(const top::CommandSpec& c, const top::FormSpec& form, top::Header h,
                            const std::string& tag, const std::string& ex) {
  const std::string id(c.ident);
  const char ctl = form.control;
  std::size_t off = 0;
  for (const top::FieldSpec& f : form.fields) {
    const std::size_t w = f.kind == FieldKind::le_i32   ? 4
                          : f.kind == FieldKind::le_i16 ? 2
                          : f.kind == FieldKind::le_u16 ? 2
                          : f.width == 0                ? ex.size() - std::min(off, ex.size())
                                                        : f.width;
    if (off + w > ex.size()) break;
    auto with_raw = [&](std::int64_t raw, const std::string& what) {
      const std::string text = encode_raw(f, raw);
      if (text.size() != w) return;
      std::string d = ex;
      d.replace(off, w, text);
      add("value", tag + std::string(f.name) + " " + what,
          frame(h, client_, c.address, ctl, id, d));
    };
    if (!f.enums.empty()) {
      std::int64_t top_value = 0;
      for (const auto& e : f.enums) {
        with_raw(e.value, std::string(e.name));
        top_value = std::max(top_value, e.value);
      }
      with_raw(top_value + 1, "one past the last value");
    } else if (f.min <= f.max && f.scale > 0) {
      const auto lo = static_cast<std::int64_t>(std::llround(f.min / f.scale));
      const auto hi = static_cast<std::int64_t>(std::llround(f.max / f.scale));
      with_raw(lo, "min");
      with_raw(hi, "max");
      with_raw(lo - 1, "min-1");
      with_raw(hi + 1, "max+1");
    }
    if (f.kind == FieldKind::hex_u || f.kind == FieldKind::hex_s) {
      std::string d = ex;
      d.replace(off, w, std::string(w, 'F'));
      add("value", tag + std::string(f.name) + " all F", frame(h, client_, c.address, ctl, id, d));
      d.replace(off, w, std::string(w, 'f'));
      add("value", tag + std::string(f.name) + " lowercase",
          frame(h, client_, c.address, ctl, id, d));
      d.replace(off, w, std::string(w, 'G'));
      add("value", tag + std::string(f.name) + " not hex",
          frame(h, client_, c.address, ctl, id, d));
    }
    off += w;
  }
}

void CaseSource::add(std::string family, std::string name, std::string bytes) {
  FuzzCase c;
  c.index = base_.size();
  c.base = c.index;
  c.family = std::move(family);
  c.name = std::move(name);
  c.bytes = std::move(bytes);
  judge(c);
  base_.push_back(std::move(c));
}

Level CaseSource::level_for(std::string_view ident, char control, std::string_view tag) const {
  if (!matrix_) return Level::must;
  std::optional<Level> best;
  for (const Case& k : matrix_->cases) {
    if (std::find(k.tags.begin(), k.tags.end(), tag) == k.tags.end()) continue;
    if (!k.applies_to(model_)) continue;
    if (!ident.empty()) {
      if (k.steps.empty() || !k.steps[0].send || k.steps[0].send->command != ident) continue;
      if (control && k.steps[0].send->control != control) continue;
    }
    if (!best || k.level < *best) best = k.level;
  }
  return best.value_or(Level::may);
}

void CaseSource::judge(FuzzCase& c) const {
  top::StreamDecoder dec;
  dec.feed(c.bytes);
  dec.flush();
  std::vector<top::Frame> frames;
  top::StreamItem item;
  auto drain = [&] {
    while (dec.next(item))
      if (item.kind == top::ItemKind::frame) frames.push_back(std::move(item.frame));
  };
  drain();
  c.open_end = dec.buffered() > 0;
  dec.finish();
  drain();
  c.frames = frames.size();
  c.addresses.clear();
  for (const auto& f : frames) c.addresses += std::string{f.src, f.dst};
  c.ident = frames.empty() ? "" : std::string(frames[0].ident_view());
  c.promise = Promise::none;
  c.level = Level::may;
  if (frames.empty()) return;
  const bool all_corrupt = std::all_of(frames.begin(), frames.end(), [](const top::Frame& f) {
    return !f.ok() &&
           (f.has(top::FindingCode::bad_checksum) || f.has(top::FindingCode::checksum_header_case));
  });
  if (all_corrupt) {
    c.promise = Promise::silence;
    c.level = level_for("", 0, "bad-checksum");
    if (c.level == Level::may && !matrix_) c.level = Level::must;
    return;
  }
  // One clean frame from the client to the command's class: the document
  // promises an answer, or ERE for what it does not define.
  if (frames.size() != 1 || c.bytes.size() != frames[0].raw.size()) return;
  const top::Frame& f = frames[0];
  if (!f.ok() || f.src != client_ || (f.control != 'r' && f.control != 'w') || !f.findings.empty())
    return;
  const top::CommandSpec* cmd = top::find_command(dialect_, f.ident_view());
  if (!cmd) {
    if (top::find_any(f.ident_view())) return;  // the other dialect's: no promise
    c.promise = Promise::error;
    c.level = level_for("", 0, "unknown-ident");
    return;
  }
  if (!cmd->supports(model_) || f.dst != cmd->address ||
      f.header != top::choose_header(dialect_, cmd->address, f.data_length))
    return;
  top::DecodeOptions o;
  o.dialect = dialect_;
  o.model = model_;
  o.role = top::Role::request;
  const top::Decoded d = top::decode(f, o);
  const bool length_known = std::any_of(cmd->forms.begin(), cmd->forms.end(), [&](const auto& fm) {
    return fm.control == f.control && fm.role != top::Role::response &&
           f.data_length >= fm.min_length && f.data_length <= fm.max_length;
  });
  if (!length_known && cmd->has_control(f.control)) {
    c.promise = Promise::error;
    c.level = level_for(cmd->ident, 0, "wrong-length");
    return;
  }
  if (!d.form || d.form->role == top::Role::response) return;
  for (const auto& fd : d.findings)
    if (fd.severity != top::Severity::info) return;
  // A write the document gives no answer (top::write_reply: Topotek's
  // set/control writes) promises none: only the form of a reply is checked.
  if (f.control == 'w' && top::write_reply(*cmd) == top::WriteReply::nothing) return;
  c.promise = Promise::answer;
  c.level = level_for(cmd->ident, f.control, "positive");
}

FuzzCase CaseSource::at(std::uint64_t index) const {
  if (index < base_.size()) return base_[index];
  std::uint64_t s = seed_ * 0x100000001B3ull ^ index;
  splitmix(s);
  const std::uint64_t pick = splitmix(s) % base_.size();
  const bool repair = splitmix(s) % 8 != 0;
  FuzzCase c;
  c.index = index;
  c.base = pick;
  c.mutated = true;
  c.repaired = repair;
  c.family = "mutation";
  c.name = "mutation of #" + std::to_string(pick) + " (" + base_[pick].name + ")" +
           (repair ? ", lengths and checksums repaired" : "");
  c.bytes = mutate(base_[pick].bytes, splitmix(s), repair);
  judge(c);
  // A mutant promises no answer or error of its own: only silence (every
  // frame corrupt) is checked, with the frame's form of every reply.
  if (c.promise != Promise::silence) c.promise = Promise::none;
  return c;
}

}  // namespace topconf
