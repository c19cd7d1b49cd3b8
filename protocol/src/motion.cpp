// The motion table of top/motion.hpp: every command that moves the gimbal and
// every attitude report, with the document section that defines it.
#include "top/motion.hpp"

#include <initializer_list>
#include <iterator>
#include <vector>

#include "catalog_data.hpp"
#include "chars.hpp"
#include "numbers.hpp"
#include "top/enum_names.hpp"

namespace top {
namespace {

constexpr std::string_view kAxis[] = {"yaw", "pitch", "roll"};
static_assert(std::size(kAxis) == axis_count);
constexpr std::string_view kKind[] = {"angle", "rate", "ptz", "attitude"};
static_assert(std::size(kKind) == static_cast<std::size_t>(MotionKind::attitude) + 1);

constexpr MotionAxis yaw(std::string_view v, std::string_view s = {}, std::int8_t sign = 1) {
  return {Axis::yaw, v, s, sign};
}
constexpr MotionAxis pitch(std::string_view v, std::string_view s = {}, std::int8_t sign = 1) {
  return {Axis::pitch, v, s, sign};
}
constexpr MotionAxis roll(std::string_view v, std::string_view s = {}, std::int8_t sign = 1) {
  return {Axis::roll, v, s, sign};
}

// A row of one to three axes.
constexpr MotionSpec row(Dialect d, std::string_view id, MotionKind k, Reference r,
                         std::initializer_list<MotionAxis> axes, std::string_view section) {
  MotionSpec m{d, id, k, r, {}, 0, section};
  for (const MotionAxis& a : axes) m.axes[m.count++] = a;
  return m;
}

constexpr Dialect S = Dialect::skydroid;
constexpr Dialect T = Dialect::topotek;
constexpr MotionKind kAngle = MotionKind::angle;
constexpr MotionKind kRate = MotionKind::rate;
constexpr MotionKind kAtt = MotionKind::attitude;
constexpr Reference B = Reference::body;
constexpr Reference E = Reference::earth;
// Topotek 4.2: "the text makes pitch down positive" (its angles are up
// positive); SkyDroid 3.2 gives pitch speed up positive.
constexpr std::int8_t kDown = -1;

// A row with field evidence of its own (see MotionSpec::field_evidence).
constexpr MotionSpec field(MotionSpec m, double unit, std::string_view evidence) {
  m.field_unit = unit;
  m.field_evidence = evidence;
  return m;
}
constexpr MotionAxis down_in_field(MotionAxis a) {
  a.field_sign = kDown;
  return a;
}
// ArduPilot's AP_Mount_Topotek sends a YPR rate as deg/s x 1.220740379
// (ANGULAR_VELOCITY_CONVERSION), tested on real units (PR #29002): one count
// is 0.8192 deg/s, not the document's 1 deg/s (table) or 0.1 deg/s (text).
constexpr double kTopotekRateUnit = 1.0 / 1.220740379;
constexpr std::string_view kYprField =
    "AP_Mount_Topotek sends YPR as yaw, pitch (down positive), roll in deg/s x 1.220740379, "
    "pitch negated since PR #29002 (https://github.com/ArduPilot/ardupilot/pull/29002, tested "
    "on real hardware)";
constexpr std::string_view kAngleField =
    "AP_Mount_Topotek sends GAY/GIP/GIR targets at 10 Hz with speed 63 (99, its maximum) and "
    "negates pitch (GIP down positive; PR #29002: angle control works on real units); the "
    "speed byte is read in the YPR rate unit (inference: ArduPilot's SIM_Topotek moves to "
    "angle targets without a speed limit)";
constexpr std::string_view kGiaField =
    "AP_Mount_Topotek.cpp @ d4209711 gimbal_angle_analyse() reads yaw, pitch, roll from GIA "
    "and negates pitch (down positive on the wire); ArduPilot's SIM_Topotek sends 30 deg down "
    "as 0BB8; a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answers the GIC query "
    "with a 12-char GIA (PixEagle session 20260917T044930Z-queries 04:49:34.243738 "
    "#TPPG2rGIC0035 -> 04:49:34.350916 #tpGPCrGIAFF25FFF8FFFE38)";

constexpr MotionSpec kMotions[] = {
    // SkyDroid 3.1-3.3
    {S, "PTZ", MotionKind::ptz, B, {}, 0, "SkyDroid 3.1"},
    row(S, "GSY", kRate, B, {yaw("speed")}, "SkyDroid 3.2"),
    row(S, "GSP", kRate, B, {pitch("speed")}, "SkyDroid 3.2"),
    row(S, "GSR", kRate, B, {roll("speed")}, "SkyDroid 3.2"),
    row(S, "GSM", kRate, B, {yaw("yaw_speed"), pitch("pitch_speed")}, "SkyDroid 3.2"),
    row(S, "GAY", kAngle, B, {yaw("angle", "speed")}, "SkyDroid 3.3.1"),
    row(S, "GAP", kAngle, B, {pitch("angle", "speed")}, "SkyDroid 3.3.1"),
    row(S, "GAR", kAngle, B, {roll("angle", "speed")}, "SkyDroid 3.3.1"),
    row(S, "GAM", kAngle, B, {yaw("yaw", "yaw_speed"), pitch("pitch", "pitch_speed")},
        "SkyDroid 3.3.1"),
    row(S, "GAC", kAtt, B, {yaw("yaw"), pitch("pitch"), roll("roll")}, "SkyDroid 3.3.2.2"),
    // Topotek 4.1-4.3
    {T, "PTZ", MotionKind::ptz, B, {}, 0, "Topotek 4.1"},
    row(T, "GSY", kRate, B, {yaw("speed")}, "Topotek 4.2"),
    row(T, "GSP", kRate, B, {pitch("speed", {}, kDown)}, "Topotek 4.2"),
    row(T, "GSR", kRate, B, {roll("speed")}, "Topotek 4.2"),
    row(T, "GSM", kRate, B, {yaw("yaw_speed"), pitch("pitch_speed", {}, kDown)}, "Topotek 4.2"),
    row(T, "RPS", kRate, B, {roll("roll_speed"), pitch("pitch_speed", {}, kDown)}, "Topotek 4.2"),
    field(
        row(T, "YPR", kRate, B,
            {yaw("yaw_speed"), pitch("pitch_speed", {}, kDown), roll("roll_speed")}, "Topotek 4.2"),
        kTopotekRateUnit, kYprField),
    field(row(T, "GAY", kAngle, B, {yaw("angle", "speed")}, "Topotek 4.3.1"), kTopotekRateUnit,
          kAngleField),
    row(T, "GAP", kAngle, B, {pitch("angle", "speed")}, "Topotek 4.3.1"),
    row(T, "GAR", kAngle, B, {roll("angle", "speed")}, "Topotek 4.3.1"),
    row(T, "GAM", kAngle, B, {yaw("yaw", "yaw_speed"), pitch("pitch", "pitch_speed")},
        "Topotek 4.3.1"),
    row(T, "GIY", kAngle, E, {yaw("angle", "speed")}, "Topotek 4.3.2"),
    field(row(T, "GIP", kAngle, E, {down_in_field(pitch("angle", "speed"))}, "Topotek 4.3.2"),
          kTopotekRateUnit, kAngleField),
    field(row(T, "GIR", kAngle, E, {roll("angle", "speed")}, "Topotek 4.3.2"), kTopotekRateUnit,
          kAngleField),
    row(T, "GIM", kAngle, E, {yaw("yaw", "yaw_speed"), pitch("pitch", "pitch_speed")},
        "Topotek 4.3.2"),
    row(T, "GAC", kAtt, B, {yaw("yaw"), pitch("pitch"), roll("roll")}, "Topotek 4.3.3"),
    row(T, "GIC", kAtt, E, {yaw("yaw"), pitch("pitch"), roll("roll")}, "Topotek 4.3.5"),
    // The field: GIA frames of 12 chars carry the attitude (pitch down positive).
    field(row(T, "GIA", kAtt, E, {yaw("yaw"), pitch("pitch", {}, kDown), roll("roll")},
              "field: ArduPilot AP_Mount_Topotek.h @ 3d293ff8, .cpp @ d4209711; PixEagle "
              "20260917T044930Z-queries"),
          0, kGiaField),
};

}  // namespace

std::string_view to_string(Axis a) noexcept { return enum_name(kAxis, a); }
std::string_view to_string(MotionKind k) noexcept { return enum_name(kKind, k); }

std::span<const MotionSpec> motions() noexcept { return kMotions; }

const MotionSpec* motion_of(Dialect d, std::string_view ident) noexcept {
  if (ident.size() != 3) return nullptr;
  for (const MotionSpec& m : kMotions)
    if (m.dialect == d && m.ident == ident) return &m;
  return nullptr;
}

namespace {
// built at start-up (the tables are constants): no guard on each call
const MotionSpec* row_of(const CommandSpec& c) noexcept { return motion_of(c.dialect, c.ident); }
const detail::PerCommand<const MotionSpec*, decltype(&row_of)> kRowOf(&row_of);
}  // namespace

const MotionSpec* motion_of(const CommandSpec& cmd) noexcept { return kRowOf(cmd); }

namespace {

// The integer of a number field's chars; false when they are not its digits.
bool read_integer(const FieldSpec& f, std::string_view bytes, std::int64_t& out) noexcept {
  if (bytes.empty() || bytes.size() > 15) return false;
  std::uint64_t v = 0;
  switch (f.kind) {
    case FieldKind::hex_u:
    case FieldKind::hex_s:
    case FieldKind::enum_hex:
      for (const char c : bytes) {
        const int h = detail::hex_value(c);
        if (h < 0) return false;
        v = v * 16 + static_cast<unsigned>(h);
      }
      out = static_cast<std::int64_t>(v);
      if (f.kind == FieldKind::hex_s && (v >> (bytes.size() * 4 - 1)) & 1u)
        out -= std::int64_t{1} << (bytes.size() * 4);
      return true;
    case FieldKind::dec_u:
      for (const char c : bytes) {
        if (c < '0' || c > '9') return false;
        v = v * 10 + static_cast<unsigned>(c - '0');
      }
      out = static_cast<std::int64_t>(v);
      return true;
    default:
      return false;
  }
}

// The field `name` of `form` in `data`: its spec and bytes, or nullptr.
const FieldSpec* field_in(const FormSpec& form, std::string_view name, std::string_view data,
                          std::string_view& bytes) noexcept {
  std::size_t at = 0;
  for (const FieldSpec& f : form.fields) {
    const std::size_t w = f.width ? f.width : data.size() - std::min(at, data.size());
    if (f.name.size() == name.size() && f.name[0] == name[0] && f.name == name) {
      if (at + w > data.size()) return nullptr;
      bytes = data.substr(at, w);
      return &f;
    }
    at += w;
  }
  return nullptr;
}

}  // namespace

bool read_motion(const MotionSpec& spec, const FormSpec& form, std::string_view data,
                 MotionReading& out, int only) noexcept {
  for (const MotionAxis& a : spec.fields()) {
    const auto i = static_cast<std::size_t>(a.axis);
    if (only >= 0 && static_cast<int>(i) != only) continue;
    std::string_view bytes;
    const FieldSpec* f = field_in(form, a.value, data, bytes);
    if (!f || !read_integer(*f, bytes, out.raw[i])) return false;
    out.value[i] = detail::scaled(out.raw[i], f->scale);
    out.min[i] = f->min;
    out.max[i] = f->max;
    out.has[i] = true;
    if (a.speed.empty()) continue;
    f = field_in(form, a.speed, data, bytes);
    if (!f || !read_integer(*f, bytes, out.speed_raw[i])) return false;
    out.speed[i] = detail::scaled(out.speed_raw[i], f->scale);
  }
  return true;
}

std::int64_t ptz_code(const FormSpec& form, std::string_view data) noexcept {
  // Every PTZ form puts its two-char action first (SkyDroid 3.1, Topotek
  // 4.1): read without the search by name, which costs most of a call.
  if (!form.fields.empty() && data.size() >= 2) {
    const FieldSpec& f = form.fields.front();
    if (f.width == 2 && f.kind == FieldKind::enum_hex && f.name == "action") {
      const int hi = detail::hex_value(data[0]), lo = detail::hex_value(data[1]);
      return hi < 0 || lo < 0 ? -1 : hi * 16 + lo;
    }
  }
  std::string_view bytes;
  std::int64_t v = -1;
  const FieldSpec* f = field_in(form, "action", data, bytes);
  return f && read_integer(*f, bytes, v) ? v : -1;
}

double motion_speed(const MotionSpec& spec, double value, std::int64_t raw, bool field) noexcept {
  return field && spec.field_unit != 0 ? static_cast<double>(raw) * spec.field_unit : value;
}

std::string_view attitude_for(const MotionSpec& spec) noexcept {
  return spec.reference == Reference::earth ? "GIC" : "GAC";
}

}  // namespace top
