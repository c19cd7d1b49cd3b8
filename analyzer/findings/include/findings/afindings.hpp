// Analyzer-level findings: problems of the capture, the transport or the
// session, not of a frame's bytes. Built like top::TOP_FINDINGS (without
// its quirk column: no analyzer finding names a firmware quirk); the
// table is documented in docs/topdump-json.md ("Analyzer findings") and
// tests/analyzer keep both in step.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "top/diagnoses.hpp"
#include "top/findings.hpp"

namespace topdump {

// X(enumerator, "stable-code", default severity, "when it fires")
#define TOPDUMP_FINDINGS(X)                                                                       \
  X(truncated_file, "truncated-file", error,                                                      \
    "the capture file ends inside a record; records before it are decoded")                       \
  X(bad_caplen, "bad-caplen", error,                                                              \
    "a pcap record's captured length exceeds the snap length or libpcap's limit; reading stops "  \
    "there, records before it are decoded")                                                       \
  X(bad_block_length, "bad-block-length", error,                                                  \
    "a pcapng block length is below 12, not a multiple of 4 or differs from its trailer; "        \
    "reading stops there")                                                                        \
  X(unknown_interface, "unknown-interface", error,                                                \
    "a pcapng packet names an interface no Interface Description Block described; reading "       \
    "stops there")                                                                                \
  X(bad_block, "bad-block", error,                                                                \
    "a pcapng block is malformed otherwise (a bad option, a second section's link type); "        \
    "reading stops there")                                                                        \
  X(snaplen_cut, "snaplen-cut", warning,                                                          \
    "a packet was cut by the snap length; its TOP bytes may be incomplete")                       \
  X(bad_packet, "bad-packet", warning, "a link, IP, UDP or TCP header is malformed or cut short") \
  X(duplicate_datagram, "duplicate-datagram", info,                                               \
    "the capture recorded a UDP datagram twice (the same IPv4 identification, "                   \
    "addresses, ports and payload within 1 s); the copy is skipped")                              \
  X(unsupported_link, "unsupported-link", error,                                                  \
    "the capture's link type is not one topdump dissects")                                        \
  X(tcp_gap, "tcp-gap", error,                                                                    \
    "bytes of a TCP stream were never captured; the decoder restarts after "                      \
    "the gap")                                                                                    \
  X(tcp_retransmission, "tcp-retransmission", info,                                               \
    "a TCP segment carries bytes already seen (retransmission or overlap)")                       \
  X(tcp_overlap_differs, "tcp-overlap-differs", warning,                                          \
    "an overlapping TCP segment disagrees with the bytes already seen; the "                      \
    "first copy is kept")                                                                         \
  X(tcp_out_of_order, "tcp-out-of-order", info,                                                   \
    "a TCP segment arrived before the bytes that precede it; it is held "                         \
    "until they come")                                                                            \
  X(reassembly_limit, "reassembly-limit", error,                                                  \
    "a TCP stream held more out-of-order bytes than the limit; held bytes "                       \
    "are dropped as a gap")                                                                       \
  X(conversation_limit, "conversation-limit", warning,                                            \
    "more live conversations than the limit; the oldest one was closed")                          \
  X(log_syntax, "log-syntax", error,                                                              \
    "a line of a serial log does not follow its format; the line is skipped")                     \
  X(unanswered, "unanswered", warning,                                                            \
    "a request got no response within the timeout (or before the end)")                           \
  X(unsolicited, "unsolicited", warning,                                                          \
    "a response that no pending request asked for (and no stream explains), "                     \
    "after the conversation's first request")                                                     \
  X(echo_differs, "echo-differs", warning,                                                        \
    "the reply to a write carries other data than the write (Topotek REC "                        \
    "and CAP answer with a file index and are exempt)")                                           \
  X(repeated, "repeated", info,                                                                   \
    "the same request again within the repeat window (some senders send "                         \
    "each frame three times, 30 ms apart); a rate command sent again is a "                       \
    "refresh, not a repeat")                                                                      \
  X(no_frames, "no-frames", error, "the input held no TOP frame at all")                          \
  X(reply_port, "reply-port", info,                                                               \
    "the device sent its frames from a port other than the one it serves (the "                   \
    "ephemeral-reply-port trait of docs/FIELD.md); they are its own, paired with the requests "   \
    "of the client's host; once per conversation")                                                \
  X(fan_out, "fan-out", info,                                                                     \
    "the device sent its frames to several ports of the client's host, or twice (the fan-out "    \
    "and duplicate-to-client-port traits); each copy is shown with the frame it copies and "      \
    "counted once; once per conversation")                                                        \
  X(silent_writes, "silent-writes", info,                                                         \
    "the device took writes the document gives no reply without a reply (the silent-writes "      \
    "trait); their effects are the evidence; once per conversation")

// The analyzer's codes: its findings, then the diagnoses of
// top/diagnoses.hpp (the one home of their codes, severities, evidence and
// remedies), so that a diagnosis is a session finding like the others:
// selected, muted, counted and in the exit status by the same code.
// The enum and the count derive from the rows as every X-macro table's do
// (top/findings.hpp: TOP_ROW_ENUMERATOR, TOP_ROW_COUNT).
enum class ACode : std::uint16_t {
  TOPDUMP_FINDINGS(TOP_ROW_ENUMERATOR) TOP_DIAGNOSES(TOP_ROW_ENUMERATOR)
};

// The analyzer findings proper (before the diagnoses).
inline constexpr std::size_t afinding_count = 0 TOPDUMP_FINDINGS(TOP_ROW_COUNT);
inline constexpr std::size_t acode_count = afinding_count + top::diagnosis_count;

// A diagnosis as an analyzer code, and back (nullopt for a finding).
constexpr ACode acode_of(top::Diagnosis d) noexcept {
  return static_cast<ACode>(afinding_count + static_cast<std::size_t>(d));
}
constexpr std::optional<top::Diagnosis> diagnosis_of(ACode c) noexcept {
  const auto i = static_cast<std::size_t>(c);
  if (i < afinding_count) return std::nullopt;
  return static_cast<top::Diagnosis>(i - afinding_count);
}

std::string_view to_string(ACode c) noexcept;
top::Severity default_severity(ACode c) noexcept;
std::string_view description(ACode c) noexcept;
std::optional<ACode> acode_from_string(std::string_view s) noexcept;

}  // namespace topdump
