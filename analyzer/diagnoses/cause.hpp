// Which causes of an unanswered request are diagnoses, in one place: the
// session hands such a request to the detector of its diagnosis (its case),
// and the report lists it under that diagnosis, not among the unanswered
// requests (report/facts.cpp).
#pragma once

#include <optional>
#include <type_traits>

#include "top/diagnoses.hpp"

namespace topdump::diag {

// The diagnosis a request unanswered for `cause` belongs to, if its cause
// is one: a bad checksum dropped-bad-checksum, lowercase checksum digits
// dropped-checksum-case, a Topotek network request with source U
// reply-interface, a device that said nothing silent-device; none for the
// others (no cause seen, not supported, invalid, answered to another port).
//
// `Cause` is topdump::Cause (why a request may go unanswered), which is
// still declared in the session (analyzer/session/events.hpp), a room this
// one may not include: a template only until that enum moves into this
// header; then this is a plain function, and its callers stay as they are.
template <class Cause>
requires std::is_enum_v<Cause>
constexpr std::optional<top::Diagnosis> diagnosis_of_cause(Cause cause) noexcept {
  if (cause == Cause::bad_checksum) return top::Diagnosis::dropped_bad_checksum;
  if (cause == Cause::checksum_case) return top::Diagnosis::dropped_checksum_case;
  if (cause == Cause::uart_source) return top::Diagnosis::reply_interface;
  if (cause == Cause::silent) return top::Diagnosis::silent_device;
  return std::nullopt;
}

}  // namespace topdump::diag
