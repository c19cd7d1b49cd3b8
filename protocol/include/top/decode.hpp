// Decoding a frame into named, typed fields with units, and encoding fields
// back into data.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "top/catalog.hpp"
#include "top/frame.hpp"

namespace top {

struct MotionSpec;  // top/motion.hpp

struct FieldValue {
  const FieldSpec* spec = nullptr;
  std::uint32_t offset = 0;    // first byte of the field in the frame
  std::uint32_t length = 0;    // bytes of the field
  bool valid = false;          // the bytes fit the kind
  bool none = false;           // the "no value" placeholder ("NNNNN")
  std::int64_t integer = 0;    // raw integer (numeric and enum kinds)
  double value = 0;            // integer * scale, or the parsed number
  std::string text;            // text, nmea source, raw bytes
  std::string_view enum_name;  // enum kinds, when the value is known
  // The record (from 1) of the form's records the field belongs to
  // (FormSpec::record: the Topotek ODR detections); 0 for a field of the
  // form itself.
  std::uint16_t record = 0;

  std::string_view name() const noexcept { return spec ? spec->name : ""; }
  std::string_view unit() const noexcept { return spec ? spec->unit : ""; }
};

// The field's key in every output (JSON, -V, CSV, the summary, the
// dissector's label): its name, and for a field of a record the record's
// number ("x[1]", "confidence[2]").
std::string field_key(const FieldValue& f);
// The same appended to `out`.
void append_key(const FieldValue& f, std::string& out);

// The value as a person reads it: "-50.00 deg", "follow (06)", "192.168.1.2".
std::string format_value(const FieldValue& f);
// The same text appended to `out` (for writers that reuse one buffer).
void append_value(const FieldValue& f, std::string& out);
// The value alone, for tables (topdump --csv): the number without its unit
// or label ("-50.00"), an enum's label (or its code when undocumented), the
// text of text fields; nothing for the "no value" placeholder or an invalid
// field. The unit is FieldValue::unit().
void append_plain_value(const FieldValue& f, std::string& out);

struct DecodeOptions {
  Dialect dialect = Dialect::unknown;  // unknown: detect from the frame
  Model model = Model::unknown;        // unknown: no model checks
  // The role as the caller knows it from the conversation (any: judged from
  // the addresses). Response says the device sent the frame: the forms
  // real firmware is recorded sending (top/device.hpp, recorded_form) then
  // name their evidence in its findings, whatever its address order.
  Role role = Role::any;
  // false: the verdict only (dialect, role, command, form, and findings with
  // codes, severities and offsets but empty messages); no field values. For
  // callers that count rather than show (topdump stats).
  bool detail = true;
  // Among the forms of one shape whose fields validate, a document's before
  // one only the field gives (false: the catalog's order, the field's echo
  // of a LAT/LON write first). A reply in both (the LRF's 5 digits) is then
  // the document's: for a reader asking whether the document allows it.
  bool document_first = false;
};

struct StreamSpec;  // top/device.hpp

struct Decoded {
  Dialect dialect = Dialect::unknown;  // the dialect decoded with
  Role role = Role::any;               // request or response as decided
  const CommandSpec* command = nullptr;
  const FormSpec* form = nullptr;
  // The command's motion row (top/motion.hpp: what moves the gimbal or
  // reports its attitude), or null.
  const MotionSpec* motion = nullptr;
  // For a write not known to come from the device (its role request or
  // any), the stream it switches as the field's firmware does
  // (stream_enabled_by, Profile::field, top/device.hpp), or null.
  const StreamSpec* switches = nullptr;
  std::vector<FieldValue> fields;
  std::vector<Finding> findings;  // catalog-level findings

  // "yaw -50.00 deg, speed 5.0 deg/s"
  std::string summary() const;
  // The same, appended to `out` (a reused buffer).
  void append_summary(std::string& out) const;
};

// The role a frame plays, judged from its addresses: a frame from U/P is a
// request, one to U/P a response.
inline Role role_from_addresses(const Frame& f) noexcept {
  const bool from_client = is_client_address(f.src), to_client = is_client_address(f.dst);
  if (from_client && !to_client) return Role::request;
  if (to_client && !from_client) return Role::response;
  return Role::any;
}

// The role a frame's layout alone gives in `dialect`: response when every
// form of its identifier and control that takes its data length is a
// response (a VSN version, a 12-char GAC or GIA attitude), request when
// every one is a request, else any (`dialect` unknown: the forms of both
// dialects together); a read of a device stream's push in a layout no
// request has is a response too (the SkyDroid GAC push). For a device that keeps the request's
// address order (ArduPilot's SITL simulators), where the addresses say
// nothing.
Role role_from_layout(Dialect dialect, const Frame& f) noexcept;

// Decodes the data of a structurally parsed frame. Never fails: unknown
// identifiers, wrong lengths and bad digits become findings.
Decoded decode(const Frame& frame, const DecodeOptions& opts = {});
// The same into `out`, reusing the capacity of its vectors (for loops over
// many frames).
void decode(const Frame& frame, const DecodeOptions& opts, Decoded& out);

// Encodes field values (in scaled units, or enum values, or text) into the
// data of a form. Values are matched to fields by position; missing trailing
// values are an error. Returns false and leaves `out` unspecified when a
// value does not fit its field.
struct EncodeValue {
  double number = 0;
  std::string_view text;  // used by text, number, nmea, enum_char, none
  bool use_text = false;
};
bool encode_fields(const FormSpec& form, std::span<const EncodeValue> values, std::string& out);

// An example data string for a form, every field mid-range (for tests,
// fuzz seeds and the simulator's defaults).
std::string example_data(const FormSpec& form);

}  // namespace top
