// Diagnoses: what went wrong between the autopilot (or ground station) and
// the gimbal, with the evidence behind it and what to change.
//
// Why here, in protocol/, and not in the analyzer: every row is a device or
// protocol rule (how these gimbals and their drivers fail in the field),
// with the evidence that records it, as top/device.hpp records traits. The
// table is the one home of the codes, titles, evidence and remedies; topsim
// and topconf can name the same codes. What is about a capture, the
// detectors that find a diagnosis in a conversation as it streams by, lives
// in analyzer/diagnoses/, one idea per file. docs/DIAGNOSES.md is generated
// from this table (analyzer/diagnoses/diagnoses_md.cpp; ctest
// generated.diagnoses_md keeps it in step).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "top/dialect.hpp"
#include "top/findings.hpp"

namespace top {

struct FormSpec;

// X(enumerator, "stable-code", severity, "title", "evidence", "remedy")
//
// The title says in one line what the capture shows; the evidence names the
// document section, the public driver's PR or issue, or the field note
// (docs/sources/ardupilot.md section 7 quotes each); the remedy says what to
// check or change.
#define TOP_DIAGNOSES(X)                                                                           \
  X(silent_device, "silent-device", warning,                                                       \
    "the device sent nothing while several requests to it went unanswered",                        \
    "field note: SkyDroid cameras take commands only once they output video (AP_Mount_SkyDroid "   \
    "header, ArduPilot PR #34155); the capture's own timing shows the silence",                    \
    "check the device's power, IP address or serial port, the port number and line speed, and "    \
    "that the capture sees the device's side of the link")                                         \
  X(reply_interface, "reply-interface", warning,                                                   \
    "a network client names itself U (the UART) in Topotek requests, whether or not the device "   \
    "answered",                                                                                    \
    "Topotek V1.1.3 2: P is the network client, U the UART's; ArduPilot PR #33803: a Topotek "     \
    "gimbal answers on the interface the source letter names, so a network client sending U "      \
    "hears nothing (the fix needed new firmware too); a real Topotek camera (PixEagle bench, VSN " \
    "1.6.26.R.D) obeyed GSY and GSP sent with U over UDP (20260917T051548Z-tilt; checkpoint "      \
    "2026-09-17-phase-5-gimbal-control-bench.md: pitch 4.9 to 7.0 to 4.7 deg)",                    \
    "send source P on UDP/TCP links (ArduPilot with PR #33803, 4.7 or later)")                     \
  X(stream_rate, "stream-rate", warning,                                                           \
    "a GAC/GIC push stream runs more than 25% off the rate its switch asked",                      \
    "document: the GAA/GIA switch (docs/FIELD.md \"Streams\") asks the device to push at a "       \
    "rate; top::stream_rate_tolerance",                                                            \
    "ask for a rate the model pushes; check the camera's load and the link when it pushes "        \
    "slower")                                                                                      \
  X(stream_stalled, "stream-stalled", warning,                                                     \
    "a push stream stopped for more than 3 periods (and 200 ms: shorter is the link's bunching) "  \
    "and then resumed",                                                                            \
    "field note: ArduPilot's SkyDroid driver counts more than 1 s without GAC as unhealthy "       \
    "and stops both axes (PR #34155 review); a running stream pushes until switched off",          \
    "check the link (Wi-Fi or UART load, lost datagrams) and the camera (reboot, video "           \
    "start) at the stall; a driver must not steer on the attitude of a stalled stream")            \
  X(stream_never_started, "stream-never-started", warning,                                         \
    "a stream was asked for and its switch answered, but no push ever came",                       \
    "field note: camera-side commands take effect only once the camera outputs video "             \
    "(AP_Mount_SkyDroid header, ArduPilot PR #34155); drivers re-send the switch every second",    \
    "start the camera's video before asking for the push, and check that the model pushes this "   \
    "stream at the rate asked")                                                                    \
  X(direction_inverted, "direction-inverted", warning,                                             \
    "angle or rate commands on an axis move the gimbal opposite to their sign",                    \
    "the C12 pitch-sign trait (docs/FIELD.md); SkyDroid 3.2 makes pitch rates up positive, "       \
    "Topotek 4.2's text down positive; ArduPilot PR #29002 negates Topotek pitch (down positive "  \
    "on the wire), tested on real units",                                                          \
    "negate that axis and kind of command in the driver, or set the model's sign switch; check "   \
    "the firmware's convention per axis and per command kind (angle and rate may differ)")         \
  X(command_ignored, "command-ignored", warning,                                                   \
    "angle commands were acknowledged but the gimbal did not move, while other commands moved it", \
    "AP_Mount_SkyDroid.cpp @ c5aa8452 (ArduPilot PR #34155): on real C11 hardware GSY is \"the "   \
    "only command confirmed to move yaw (GAM/GSM/GAY all silently ignored)\"",                     \
    "use the per-axis commands this firmware moves on (on a C11 GSY and GSP, not GAM, GSM, GAY "   \
    "or GAP), or update the firmware")                                                             \
  X(attitude_stale, "attitude-stale", warning,                                                     \
    "non-zero motion commands kept coming while the attitude feedback had stopped for more "       \
    "than 1 s",                                                                                    \
    "review of ArduPilot PR #34155: its SkyDroid driver counts more than 1 s without GAC as "      \
    "unhealthy and stops both axes; a driver closing its loop on a frozen attitude slews the "     \
    "gimbal",                                                                                      \
    "stop the axes (zero rates) when the attitude is older than 1 s, and find why the "            \
    "feedback stopped (stream-stalled, the link)")                                                 \
  X(axis_left_moving, "axis-left-moving", warning,                                                 \
    "the last rate command on an axis was non-zero, no stop followed, and the gimbal kept "        \
    "moving to the end",                                                                           \
    "QGroundControl issue #13580: after both rate buttons are released, one axis keeps its "       \
    "+40 deg/s and the gimbal keeps spinning; ArduPilot PR #30872: without a new rate command "    \
    "the last one stays with the gimbal, which keeps spinning (a zero rate after a timeout)",      \
    "send a zero rate (or PTZ stop) when the axis should stop; do not rely on the firmware's "     \
    "refresh timeout, which not every model has")                                                  \
  X(placeholder_identity, "placeholder-identity", warning,                                         \
    "an identity reply (model name, serial number, version) is a factory placeholder",             \
    "ArduPilot PR #27568: a real unit's model name reads 000000000 (not set at production); "      \
    "PR #27053: the model version is reported as Unknown",                                         \
    "have the vendor set the identity at production or update the firmware; do not choose "        \
    "model-specific behaviour from this reply")                                                    \
  X(clock_offset, "clock-offset", warning,                                                         \
    "the time set on or reported by the camera is more than a day off the capture's clock",        \
    "review of ArduPilot PR #34155: TIM sent with the 0-based month (every date one month "        \
    "early, month 00 in January); the camera's default time is 1970-01-01 (AP_Mount_SkyDroid "     \
    "header, confirmed on real hardware)",                                                         \
    "send the month 1-based and set the time from GPS after boot; whole hours off are a time "     \
    "zone (SkyDroid takes UTC), not this")                                                         \
  X(tracking_refused, "tracking-refused", warning,                                                 \
    "a tracking request was answered with a state that refuses it (Topotek TRC state 4)",          \
    "ArduPilot PR #31768: TRC state 4 (0x34) means this lens does not support tracking; PR "       \
    "#27568 reads the state from TRC's data char 1",                                               \
    "select a lens or camera that tracks, or turn tracking off for this payload")                  \
  X(dropped_bad_checksum, "dropped-bad-checksum", warning,                                         \
    "requests with a bad checksum went unanswered: the device dropped them",                       \
    "field note: ArduPilot's Topotek and SkyDroid parsers and SITL simulators drop a frame "       \
    "whose checksum does not match (docs/sources/ardupilot.md section 7)",                         \
    "fix the sender's checksum: the byte sum of every char before it, mod 256, as two "            \
    "uppercase hex digits")                                                                        \
  X(dropped_checksum_case, "dropped-checksum-case", warning,                                       \
    "requests whose checksum is right but lowercase went unanswered: the device dropped them",     \
    "field note: ArduPilot's parsers compare the checksum with uppercase hex only and drop "       \
    "the frame silently (docs/sources/ardupilot.md section 7)",                                    \
    "write the checksum digits in uppercase")                                                      \
  X(baud_mismatch, "baud-mismatch", error,                                                         \
    "a serial log holds no TOP framing, only bytes that look like a mis-set line speed",           \
    "ArduPilot's SERIALn_BAUD defaults to 57600 while the documents and the Topotek wiki set "     \
    "115200 (SERIAL2_BAUD 115; docs/sources/ardupilot.md section 7)",                              \
    "set both ends and the logger to the same line speed (115200 per the documents)")              \
  X(refresh_gap, "refresh-gap", warning,                                                           \
    "a rate command was not refreshed within the model's limit: the motors stop",                  \
    "the speed-refresh trait (docs/FIELD.md): the firmware stops a rate command that is not "      \
    "sent again in time; ArduPilot's SkyDroid driver re-sends every update",                       \
    "re-send rate commands faster than the limit for as long as the axis should move")

enum class Diagnosis : std::uint8_t { TOP_DIAGNOSES(TOP_ROW_ENUMERATOR) };

inline constexpr std::size_t diagnosis_count = 0 TOP_DIAGNOSES(TOP_ROW_COUNT);

// The stable code, e.g. "stream-stalled".
std::string_view to_string(Diagnosis d) noexcept;
Severity severity(Diagnosis d) noexcept;
std::string_view title(Diagnosis d) noexcept;
std::string_view evidence(Diagnosis d) noexcept;
std::string_view remedy(Diagnosis d) noexcept;
std::optional<Diagnosis> diagnosis_from_string(std::string_view s) noexcept;

// ---- the device rules the detectors ask --------------------------------

// An identity value (model name, serial number, version) that is a factory
// placeholder: all zeros (000000000, 0.0.0), 123, 1.2.3, Unknown (any
// case), or empty (docs/sources/ardupilot.md section 1.4).
bool is_placeholder_identity(std::string_view value) noexcept;

// Whether the device's reply to `ident` names the device: Topotek PA2
// (model name), VSN (version), VER (serial number); SkyDroid VER
// (software version) and MOD (model name, which ArduPilot's SkyDroid
// driver reads until answered: docs/sources/ardupilot.md).
// Inline: the session asks it of every device frame.
inline bool is_identity_reply(Dialect d, std::string_view id) noexcept {
  if (id.size() != 3) return false;
  if (d == Dialect::topotek) return id == "PA2" || id == "VSN" || id == "VER";
  return d == Dialect::skydroid && (id == "VER" || id == "MOD");
}

// Whether a device's reply says its tracker drives the gimbal: Topotek TRC
// with state '2' (tracking; data char 1, as refuses_tracking reads it).
// ArduPilot's AP_Mount_Topotek starts tracking with TRC 02 and a LOC, reads
// TRC, and sends no motion command while the camera tracks (PR #27568): the
// motion the tracker makes is no answer to the commands before it. A LOC
// alone is not enough: a lens that waits (state 1) does not move. A read's
// reply (`control` 'r'): the echo of the write TRC 02 (prepare) is no state.
inline bool reports_tracking(Dialect d, std::string_view id, char control,
                             std::string_view data) noexcept {
  return control == 'r' && data.size() == 2 && data[1] == '2' && d == Dialect::topotek &&
         id == "TRC";
}

// Whether a device's frame says its tracker lets the gimbal go: a TRC read
// answered with state 0 (stopped), 1 (waiting) or 4 (this lens does not
// track), or the echo of the write TRC 00 (exit) or 01 (cancel to waiting)
// (docs/CATALOG.md, TRC; AP_Mount_Topotek cancels with them, PR #27568).
// State 3 (temporarily lost) is not: the tracker may take the target again.
inline bool releases_tracking(Dialect d, std::string_view id, char control,
                              std::string_view data) noexcept {
  if (d != Dialect::topotek || id != "TRC" || data.size() != 2) return false;
  if (control == 'r') return data[1] == '0' || data[1] == '1' || data[1] == '4';
  return control == 'w' && data[0] == '0' && (data[1] == '0' || data[1] == '1');
}

// Whether a device's reply refuses tracking: Topotek TRC with state '4'
// (data char 1; ArduPilot PR #31768). State 3 (temporarily lost) is not a
// refusal.
inline bool refuses_tracking(Dialect d, std::string_view id, std::string_view data) noexcept {
  return data.size() == 2 && data[1] == '4' && d == Dialect::topotek && id == "TRC";
}

// Whether frames of `ident` may carry a date (a form with year, month and
// day fields): TIM and UTC in both dialects' catalogs (a test checks the
// catalog has no other).
inline bool carries_date(std::string_view id) noexcept { return id == "TIM" || id == "UTC"; }

// A date and time carried by a frame: the fields named year, month, day,
// hour, minute and second of its form (Topotek TIM and UTC, SkyDroid TIM),
// read from the raw data by the form's field widths, so it works without
// decoded values. Two-digit years are 1969-2068 (POSIX %y). nullopt when the form has no
// year/month/day or a digit is not one.
struct DateTime {
  int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
};
std::optional<DateTime> date_time_of(const FormSpec& form, std::string_view data) noexcept;
// Seconds since 1970-01-01 of a date (proleptic Gregorian, UTC); months
// outside 1..12 are taken as they come (month 0 is the December before).
std::int64_t epoch_seconds(const DateTime& t) noexcept;

// How long without an attitude report a driver takes its attitude as stale:
// ArduPilot's SkyDroid driver counts more than 1 s without GAC as unhealthy
// (review of PR #34155).
inline constexpr std::int64_t attitude_stale_ms = 1000;

// The shortest stop of a push stream that is the stream's, not the link's:
// Wi-Fi and UDP bridges hand frames over in bunches of 60-100 ms (an outside
// capture of a 50 Hz GAC stream, whose 3 periods are 60 ms, gave 73
// "stalls"); ArduPilot's own health check waits attitude_stale_ms.
inline constexpr std::int64_t stream_stall_min_ms = 200;

}  // namespace top
