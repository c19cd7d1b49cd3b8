// Why a request may go unanswered, as far as the capture shows: the session
// decides it once per request (session/requests.cpp, cause_of) and every
// room reads it as a value. Four causes are diagnoses (diagnosis_of): the
// report lists those as diagnoses, not as unanswered requests.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "top/diagnoses.hpp"

namespace topdump {

enum class Cause : std::uint8_t {
  none,
  bad_checksum,   // devices drop frames they cannot trust
  checksum_case,  // a lowercase checksum: strict parsers drop it
  uart_source,    // Topotek: source U over the network, answers go to the UART
  unsupported,    // not in the catalog, or not on the model
  invalid,        // a wrong length or value: Topotek ignores it, SkyDroid answers ERE
  other_port,     // the device sent its frames to another port of the client's host
  silent          // the device sent nothing while several requests went unanswered
};
inline constexpr std::size_t cause_count = static_cast<std::size_t>(Cause::silent) + 1;

// What the capture shows of that cause, for people ("" for none).
std::string_view describe(Cause c) noexcept;

// The diagnosis a cause is (dropped-bad-checksum, dropped-checksum-case,
// reply-interface, silent-device), or none: the one mapping.
constexpr std::optional<top::Diagnosis> diagnosis_of(Cause c) noexcept {
  switch (c) {
    case Cause::bad_checksum:
      return top::Diagnosis::dropped_bad_checksum;
    case Cause::checksum_case:
      return top::Diagnosis::dropped_checksum_case;
    case Cause::uart_source:
      return top::Diagnosis::reply_interface;
    case Cause::silent:
      return top::Diagnosis::silent_device;
    default:
      return std::nullopt;
  }
}

}  // namespace topdump
