// Commands that move the gimbal, and the attitude that shows where it is:
// which identifier is an angle target, a rate, a PTZ action or an attitude
// report, on which axes, in which fields, and which way a positive value
// turns. topsim moves its axes by this table, topdump's report compares
// commands with the attitude by it, and the diagnoses read it.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>

#include "top/catalog.hpp"
#include "top/dialect.hpp"

namespace top {

enum class Axis : std::uint8_t { yaw, pitch, roll };
std::string_view to_string(Axis a) noexcept;  // "yaw", "pitch", "roll"
inline constexpr std::size_t axis_count = 3;

enum class MotionKind : std::uint8_t {
  angle,    // a target angle per axis, with an optional speed to reach it
  rate,     // a turning rate per axis, held until refreshed or changed
  ptz,      // a PTZ action code (directions, stop, centre)
  attitude  // the gimbal's reported angles
};
std::string_view to_string(MotionKind k) noexcept;  // "angle", "rate", "ptz", "attitude"

// The frame of reference of an angle or attitude.
enum class Reference : std::uint8_t {
  body,  // relative to the aircraft (magnetic encoder: GA* on Topotek, all SkyDroid)
  earth  // in the earth frame (gyroscope: Topotek GI*, 4.3.2)
};

// The turn from one yaw to another `d` degrees on, the short way round:
// std::remainder(d, 360.0), d less the nearest multiple of 360 (a tie to
// the even one), in [-180, 180]. Inline, for callers that take it of every
// attitude (tests/motion_test.cpp checks it against std::remainder; why
// not remainder(): docs/perf/decisions.md). Adding and taking back 1.5 * 2^52
// rounds d / 360 to an integer, ties to even (IEEE arithmetic: the build
// never uses -ffast-math), and d less a multiple of 360 within 180 of it
// is exact.
inline double short_way(double d) noexcept {
  constexpr double kRound = 0x1.8p52;
  const double n = (d / 360.0 + kRound) - kRound;
  const double r = d - n * 360.0;
  return r == 0 ? std::copysign(0.0, d) : r;  // a zero takes d's sign, as remainder's
}

// One axis of a motion command: the field that carries its value and, for
// angles, the field of the speed to reach it.
struct MotionAxis {
  Axis axis = Axis::yaw;
  std::string_view value;  // "angle", "yaw", "speed", "yaw_speed"
  std::string_view speed;  // angles: "speed", "yaw_speed"; empty for rates
  // The sign of a positive value as the document writes it: +1 when a
  // positive value turns right (yaw) or up (pitch), -1 when it turns down.
  std::int8_t sign = 1;
  // The sign field evidence gives where it differs from the document's
  // (0: the same); the row's field_evidence names the source.
  std::int8_t field_sign = 0;
  // The sign under field evidence (`field`, the field profile) or the document.
  constexpr std::int8_t sign_in(bool field) const noexcept {
    return field && field_sign != 0 ? field_sign : sign;
  }
};

struct MotionSpec {
  Dialect dialect = Dialect::unknown;
  std::string_view ident;
  MotionKind kind = MotionKind::angle;
  Reference reference = Reference::body;
  std::array<MotionAxis, axis_count> axes{};
  std::uint8_t count = 0;    // axes used
  std::string_view section;  // where the document says so
  // Under field evidence: deg/s of one raw count of the speed (angles) or
  // rate fields, where the field's unit is not the catalog's (0: the
  // catalog's scale).
  double field_unit = 0;
  // The source of every field_sign, of field_unit and of a row only the
  // field gives (Topotek GIA attitude); empty: the document alone.
  std::string_view field_evidence;
  std::span<const MotionAxis> fields() const noexcept { return {axes.data(), count}; }
};

// The speed or rate in deg/s of a decoded field of `spec` (`value` scaled by
// the catalog, `raw` its integer) under field evidence or the document.
double motion_speed(const MotionSpec& spec, double value, std::int64_t raw, bool field) noexcept;

// Every motion command and attitude report of both dialects.
std::span<const MotionSpec> motions() noexcept;
// The row of `ident` in dialect `d`, or nullptr.
const MotionSpec* motion_of(Dialect d, std::string_view ident) noexcept;
// The row of a decoded frame's command (the catalog entry decode() found),
// or nullptr: constant time, for callers that ask it of every frame.
const MotionSpec* motion_of(const CommandSpec& cmd) noexcept;

// The values a motion frame carries, read from its data by its form's
// fields without decoding the rest (a detector reads only the frames it
// judges). Per axis: `value` scaled by the catalog (deg, deg/s), `raw` its
// integer, and for angles `speed` (scaled) and `speed_raw`.
struct MotionReading {
  std::array<double, axis_count> value{}, speed{};
  // the value field's range (min > max: none), scaled
  std::array<double, axis_count> min{}, max{};
  std::array<std::int64_t, axis_count> raw{}, speed_raw{};
  std::array<bool, axis_count> has{};
};
// false when a field of `spec` is missing from `form`, or is not a number
// (hex_u, hex_s or dec_u digits) in `data`. `only` (an Axis): that axis
// alone, for a reader that needs one.
bool read_motion(const MotionSpec& spec, const FormSpec& form, std::string_view data,
                 MotionReading& out, int only = -1) noexcept;
// A PTZ frame's action code (its "action" field), or -1.
std::int64_t ptz_code(const FormSpec& form, std::string_view data) noexcept;
// Whether `attitude`'s readings follow field evidence (Topotek GIA: a row
// only the field gives). Commands judged against it are then read with
// their field signs (MotionAxis::sign_in), against a document's report
// with the document's: a client and device of one convention agree.
inline bool field_convention(const MotionSpec& attitude) noexcept {
  return !attitude.field_evidence.empty() && attitude.kind == MotionKind::attitude;
}

// The attitude report a command of `spec` is judged against: the one of the
// same reference frame (Topotek GIC for GI* commands, GAC otherwise).
std::string_view attitude_for(const MotionSpec& spec) noexcept;

// PTZ action codes that move or stop an axis (SkyDroid 3.1 and Topotek 4.1
// agree on 00-05: stop, up, down, left, right, centre).
enum class PtzMove : std::uint8_t { none, stop, turn, centre };
struct PtzAction {
  PtzMove move = PtzMove::none;
  Axis axis = Axis::yaw;  // turn
  std::int8_t sign = 0;   // turn: +1 right/up, -1 left/down
};
// What PTZ code `code` does. C13 codes 0E-13 (pitch, yaw and roll trim, +
// then -) turn an axis only where field evidence says the model takes them
// (field_supported in top/device.hpp); the caller asks that. Inline: the
// session asks it for every PTZ write.
constexpr PtzAction ptz_action(std::int64_t code) noexcept {
  switch (code) {
    case 0x00:
      return {PtzMove::stop, Axis::yaw, 0};
    case 0x01:  // up
      return {PtzMove::turn, Axis::pitch, 1};
    case 0x02:  // down
      return {PtzMove::turn, Axis::pitch, -1};
    case 0x03:  // left
      return {PtzMove::turn, Axis::yaw, -1};
    case 0x04:  // right
      return {PtzMove::turn, Axis::yaw, 1};
    case 0x05:
      return {PtzMove::centre, Axis::yaw, 0};
    case 0x0E:  // C13 field evidence: 0E/0F pitch +/-, 10/11 yaw, 12/13 roll
    case 0x0F:
    case 0x10:
    case 0x11:
    case 0x12:
    case 0x13: {
      constexpr Axis kTrim[] = {Axis::pitch, Axis::yaw, Axis::roll};
      return {PtzMove::turn, kTrim[(code - 0x0E) / 2], static_cast<std::int8_t>(code % 2 ? -1 : 1)};
    }
    default:
      return {};
  }
}

}  // namespace top
