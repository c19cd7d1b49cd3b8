// Findings: every deviation from the TOP documents, with a stable code.
//
// The table below is the one home of the finding codes; docs/FINDINGS.md
// documents it and tests/findings_test.cpp keeps both in step.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace top {

// Severity of a finding, like a compiler diagnostic.
enum class Severity : std::uint8_t { info, warning, error };

std::string_view to_string(Severity s) noexcept;

// X(enumerator, "stable-code", default severity, "quirk id", "when it fires")
//
// The quirk id names the firmware or document behaviour a code matches
// (Finding::quirk, the "quirk" key in JSON; docs/FINDINGS.md "Quirks"), empty
// for a code that is no such behaviour.
#define TOP_FINDINGS(X)                                                                           \
  X(bad_checksum, "bad-checksum", error, "",                                                      \
    "the checksum digits do not match the byte sum; carries the expected "                        \
    "value")                                                                                      \
  X(checksum_header_case, "checksum-header-case", error, "skydroid-doc-header-case",              \
    "the checksum matches the sum of the frame with another case variant of "                     \
    "the header (SkyDroid GAY/GOT examples: computed as #tp, sent as #TP)")                       \
  X(checksum_case, "checksum-case", warning, "",                                                  \
    "the checksum is right but written with lowercase hex digits; strict "                        \
    "receivers drop it")                                                                          \
  X(no_checksum, "no-checksum", error, "",                                                        \
    "the frame ends where its two checksum digits should be")                                     \
  X(length_mismatch, "length-mismatch", warning, "",                                              \
    "the declared length fails the checksum but exactly one other data "                          \
    "length validates; decoded with that one, both lengths given")                                \
  X(tp_length, "tp-length", warning, "",                                                          \
    "a #TP (fixed) frame whose length is not 2; decoded with its length "                         \
    "char (info for SkyDroid G-class commands, which the document puts "                          \
    "under #TP)")                                                                                 \
  X(bad_header, "bad-header", error, "", "a '#' not followed by one of #TP #tp #tP #Tp")          \
  X(bad_address, "bad-address", error, "", "a source or destination address outside U M D E P G") \
  X(bad_control, "bad-control", error, "", "a control char other than r or w")                    \
  X(bad_length_char, "bad-length-char", error, "",                                                \
    "the length char of a #TP/#tp frame is not a hex digit")                                      \
  X(bad_ident, "bad-ident", error, "", "the identifier is not three uppercase letters or digits") \
  X(truncated, "truncated", error, "", "the input ends inside a frame")                           \
  X(trailing_bytes, "trailing-bytes", warning, "",                                                \
    "bytes after a complete frame in a buffer meant to hold one frame")                           \
  X(garbage, "garbage", warning, "", "bytes between frames that belong to no frame were skipped") \
  X(crlf, "crlf", info, "",                                                                       \
    "the frame is followed by CR and/or LF, which the documents do not "                          \
    "define")                                                                                     \
  X(lowercase_hex, "lowercase-hex", info, "",                                                     \
    "hex data or length digits written in lowercase (sent by autopilots "                         \
    "until 2024)")                                                                                \
  X(frame_too_long, "frame-too-long", error, "",                                                  \
    "the declared length exceeds the configured maximum")                                         \
  X(tmp_quirk, "tmp-quirk", info, "topotek-tmp-length",                                           \
    "the malformed Topotek TMP frame (12.2): documented #PDP16TMP form or "                       \
    "two-digit length #tpDP16wTMP; decoded, a known firmware quirk")                              \
  X(two_digit_length, "two-digit-length", warning, "",                                            \
    "a #tp frame whose length is written as two hex digits (the TMP quirk "                       \
    "seen on another identifier)")                                                                \
  X(ext_header_skydroid, "ext-header-dialect", warning, "",                                       \
    "an extended header (#tP/#Tp) in SkyDroid traffic, which only Topotek "                       \
    "defines")                                                                                    \
  X(unknown_ident, "unknown-ident", warning, "",                                                  \
    "the identifier is not in the catalog of the dialect")                                        \
  X(unsupported_on_model, "unsupported-on-model", error, "",                                      \
    "the command exists but neither the document nor field evidence lists it "                    \
    "for the model; information naming the evidence when the field says the "                     \
    "firmware takes it (C13 PTZ, GSY, GAC)")                                                      \
  X(unsupported_control, "unsupported-control", warning, "",                                      \
    "the command exists but not in this form (a read of a write-only "                            \
    "command or the reverse)")                                                                    \
  X(data_length, "data-length", warning, "",                                                      \
    "the data length is not one the command's layout allows")                                     \
  X(bad_field, "bad-field", warning, "",                                                          \
    "a field's characters do not fit its type (non-hex in a hex field)")                          \
  X(value_out_of_range, "value-out-of-range", warning, "",                                        \
    "a field's value is outside the range or enum the document gives")                            \
  X(error_reply, "error-reply", warning, "",                                                      \
    "the device answered ERE: it rejected a command as invalid")                                  \
  X(unswapped_addresses, "unswapped-addresses", info, "",                                         \
    "a response that keeps the request's address order (some simulators)")                        \
  X(length_in_bytes, "length-in-bytes", info, "skydroid-length-in-bytes",                         \
    "the length char counts the bytes of a hex-coded value, half its chars, in a form recorded "  \
    "from real devices (#TPDU1rIMG palette, #TPDU2rSLR0018BE range); decoded by the checksum. "   \
    "Another wrong length stays length-mismatch")                                                 \
  X(double_checksum, "double-checksum", info, "c10pro-double-checksum",                           \
    "a valid frame followed by a second checksum over it and its checksum (a C10 Pro tool's "     \
    "#TPUG2wPTZ056FEB); the two digits are taken as the frame's, not as garbage")

// A table row's enumerator, and 1 for each row: what every X-macro table
// (this one, TOP_DIAGNOSES, topdump's TOPDUMP_FINDINGS) derives its enum
// and count from, whatever its columns.
#define TOP_ROW_ENUMERATOR(e, ...) e,
#define TOP_ROW_COUNT(...) +1  // NOLINT(bugprone-macro-parentheses)

enum class FindingCode : std::uint16_t { TOP_FINDINGS(TOP_ROW_ENUMERATOR) };

inline constexpr std::size_t finding_code_count = 0 TOP_FINDINGS(TOP_ROW_COUNT);

// The stable code string, e.g. "bad-checksum".
std::string_view to_string(FindingCode c) noexcept;
// The default severity of a code.
Severity default_severity(FindingCode c) noexcept;
// One line that says when the code fires.
std::string_view description(FindingCode c) noexcept;
// The firmware or document quirk the code matches, e.g.
// quirk_id(FindingCode::tmp_quirk) == "topotek-tmp-length"; empty for most.
std::string_view quirk_id(FindingCode c) noexcept;
// Reverse lookup of a stable code string.
std::optional<FindingCode> finding_code_from_string(std::string_view s) noexcept;

// One finding. `offset` is relative to the start of the frame (or of the
// skipped bytes for stream-level findings). `quirk` names the firmware
// behaviour the finding matches, empty when it is plain corruption.
struct Finding {
  FindingCode code{};
  Severity severity{};
  std::uint32_t offset = 0;
  std::string message;
  std::string_view quirk;
};

// Exchanges two findings (their texts change hands, nothing is copied).
void swap(Finding& a, Finding& b) noexcept;

// Builds a finding with the code's default severity.
Finding make_finding(FindingCode code, std::uint32_t offset, std::string message,
                     std::string_view quirk = {});

}  // namespace top
