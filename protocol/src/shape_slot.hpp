// Internal: what a DecodeCache (top/detail/decode_cache.hpp) keeps per
// frame shape, and the key of a shape.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>

#include "decode_plan.hpp"
#include "top/decode.hpp"
#include "top/detail/decode_cache.hpp"

namespace top::detail {

// What decode() without detail found for one shape.
struct ShapeSlot {
  static constexpr std::size_t kFindings = 3;  // a shape with more is not remembered
  std::uint64_t key = 0;
  bool known = false;  // the members below are the key's
  Dialect dialect = Dialect::unknown;
  Role role = Role::any;
  std::uint8_t count = 0;
  const CommandSpec* command = nullptr;
  const FormSpec* form = nullptr;
  const MotionSpec* motion = nullptr;
  const StreamSpec* switches = nullptr;
  bool diagnosed = false;     // may_matter_to_diagnoses (top/detail/prefilter.hpp)
  std::uint8_t noted = 0xFF;  // the finding note_device_form added (0xFF: none)
  const FormPlan* plan = nullptr;
  struct Seen {
    FindingCode code{};
    Severity severity{};
    std::uint32_t offset = 0;
    std::string_view quirk;
  };
  std::array<Seen, kFindings> findings{};
};

// The key of a shape: everything decode_shape reads of the frame and the
// options (messages aside), each in its own bits of one word:
//
//   bit 63     1 (a key is never 0, the empty slot's)
//   58         whether the caller said the device sent it (Role::response:
//              note_device_form then completes the findings)
//   56-57      whether the source, the destination is a client's address
//              (note_device_form reads their order)
//   54-55      dialect          (3 values)
//   52-53      role             (3 values)
//   44-51      identifier char 0 (a byte)
//   36-43      identifier char 1
//   28-35      identifier char 2
//   25-27      header           (5 values)
//   17-24      declared length  (0-255; longer: no key)
//   15-16      control          (none, r, w; any other: no key)
//    7-14      data length      (0-255; longer: no key)
//    3-6       data offset      (0-15; past it: no key)
//    0-2       model            (7 values)
struct ShapeBits {
  unsigned shift, width;
  constexpr std::uint64_t mask() const { return ((std::uint64_t{1} << width) - 1) << shift; }
  constexpr std::uint64_t put(std::uint64_t v) const { return v << shift; }
  constexpr bool holds(std::uint64_t max) const { return max < (std::uint64_t{1} << width); }
};
inline constexpr ShapeBits kKeyModel{0, 3}, kKeyDataOffset{3, 4}, kKeyDataLength{7, 8},
    kKeyControl{15, 2}, kKeyDeclared{17, 8}, kKeyHeader{25, 3}, kKeyIdent2{28, 8},
    kKeyIdent1{36, 8}, kKeyIdent0{44, 8}, kKeyRole{52, 2}, kKeyDialect{54, 2},
    kKeyFromClient{56, 1}, kKeyToClient{57, 1}, kKeyDevice{58, 1}, kKeyMark{63, 1};
inline constexpr ShapeBits kKeyFields[] = {
    kKeyModel,   kKeyDataOffset, kKeyDataLength, kKeyControl, kKeyDeclared,
    kKeyHeader,  kKeyIdent2,     kKeyIdent1,     kKeyIdent0,  kKeyRole,
    kKeyDialect, kKeyFromClient, kKeyToClient,   kKeyDevice,  kKeyMark};

// No two fields share a bit, and every enum fits its field.
static_assert([] {
  std::uint64_t seen = 0;
  for (const ShapeBits& b : kKeyFields) {
    if (b.shift + b.width > 64 || (seen & b.mask()) != 0) return false;
    seen |= b.mask();
  }
  return true;
}());
static_assert(kKeyModel.holds(static_cast<std::uint64_t>(Model::sip)));
static_assert(kKeyHeader.holds(static_cast<std::uint64_t>(Header::tmp_quirk)));
static_assert(kKeyRole.holds(static_cast<std::uint64_t>(Role::any)));
static_assert(kKeyDialect.holds(static_cast<std::uint64_t>(Dialect::topotek)));
static_assert(kKeyControl.holds(2) && kKeyIdent0.holds(0xFF) && kKeyDeclared.holds(0xFF) &&
              kKeyDataLength.holds(0xFF) && kKeyDataOffset.holds(0xF));

// 0 when a length, the data offset or the control does not fit (those frames
// are decoded without the cache).
// `device`: the caller said the device sent it (DecodeOptions::role).
inline std::uint64_t shape_key(const Frame& f, Dialect d, Role role, Model model,
                               bool device) noexcept {
  if (f.declared_length > 0xFF || f.data_length > 0xFF || f.data_offset > 0xF) return 0;
  const std::uint64_t control = f.control == 0     ? 0
                                : f.control == 'r' ? 1
                                : f.control == 'w' ? 2
                                                   : 3;
  if (control == 3) return 0;
  const auto byte = [](char c) { return std::uint64_t{static_cast<unsigned char>(c)}; };
  return kKeyMark.put(1) | kKeyDialect.put(static_cast<std::uint64_t>(d)) |
         kKeyRole.put(static_cast<std::uint64_t>(role)) | kKeyIdent0.put(byte(f.ident[0])) |
         kKeyIdent1.put(byte(f.ident[1])) | kKeyIdent2.put(byte(f.ident[2])) |
         kKeyHeader.put(static_cast<std::uint64_t>(f.header)) |
         kKeyDeclared.put(f.declared_length) | kKeyControl.put(control) |
         kKeyDataLength.put(f.data_length) | kKeyDataOffset.put(f.data_offset) |
         kKeyModel.put(static_cast<std::uint64_t>(model)) |
         kKeyFromClient.put(is_client_address(f.src) ? 1 : 0) |
         kKeyToClient.put(is_client_address(f.dst) ? 1 : 0) | kKeyDevice.put(device ? 1 : 0);
}

struct CacheAccess {
  // The slot of a key, emptied when it held another shape. A slot is the top
  // bits of the key's product with a 64-bit odd constant: every bit of the
  // key reaches them (the low bits of a product see only the key's low bits,
  // where shapes of different identifiers look alike).
  static ShapeSlot& slot(DecodeCache& c, std::uint64_t key) {
    if (!c.slots_) c.slots_ = std::make_unique<ShapeSlot[]>(c.count_);  // at the first lookup
    ShapeSlot& s =
        c.slots_[static_cast<std::size_t>(((key * 0x9E3779B97F4A7C15ull) >> 32) >> c.shift_)];
    if (s.key != key) {  // another shape's: forget it all
      ++c.misses_;
      s.key = key;
      s.known = false;
      s.plan = nullptr;
    }
    return s;
  }
};

// Used by decode() for every frame, so inline.
// The cache's slot for this frame's shape, or null (no cache, or a shape it
// does not key).
inline ShapeSlot* shape_slot(DecodeCache* cache, const DecodeOptions& opts, const Frame& f,
                             Dialect d, Role role) {
  if (!cache) return nullptr;
  const std::uint64_t key = shape_key(f, d, role, opts.model, opts.role == Role::response);
  return key ? &CacheAccess::slot(*cache, key) : nullptr;
}

// What decode_frame's `noted` holds when note_device_form added no finding.
inline constexpr std::size_t kNoNote = static_cast<std::size_t>(-1);

// The shape's members of a Decoded, the same names in a ShapeSlot: copied
// one way by remember(), the other by replay().
template <class To, class From>
void copy_shape(To& to, const From& from) noexcept {
  to.dialect = from.dialect;
  to.role = from.role;
  to.command = from.command;
  to.form = from.form;
  to.motion = from.motion;
  to.switches = from.switches;
}

inline void remember(ShapeSlot& s, const Decoded& out, std::size_t noted, bool diagnosed) {
  if (out.findings.size() > ShapeSlot::kFindings) return;
  copy_shape(s, out);
  s.diagnosed = diagnosed;
  s.plan = out.form ? &plan_of(*out.command, *out.form) : nullptr;
  s.count = static_cast<std::uint8_t>(out.findings.size());
  s.noted = noted == kNoNote ? 0xFF : static_cast<std::uint8_t>(noted);
  for (std::size_t i = 0; i < out.findings.size(); ++i) {
    const Finding& f = out.findings[i];
    s.findings[i] = {f.code, f.severity, f.offset, f.quirk};
  }
  s.known = true;
}

inline void replay(const ShapeSlot& s, Decoded& out, std::size_t& noted, bool& diagnosed) {
  if (s.noted != 0xFF) noted = s.noted;
  copy_shape(out, s);
  diagnosed = s.diagnosed;
  for (std::size_t i = 0; i < s.count; ++i) {
    const ShapeSlot::Seen& x = s.findings[i];
    out.findings.push_back(Finding{x.code, x.severity, x.offset, std::string(), x.quirk});
  }
}

}  // namespace top::detail
