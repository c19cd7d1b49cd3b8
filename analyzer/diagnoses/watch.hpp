// The detectors of one conversation, in one place: the session holds one
// Watch per conversation (and a StallWatch and NeverStartedWatch per
// stream, session/stats.hpp) and hands it the frames it already decoded;
// at the conversation's end verdicts() yields what was found. Every
// detector registered here has its row in top/diagnoses.hpp; its state is
// a few numbers, whatever the capture's length.
#pragma once

#include "diagnoses/baud_mismatch.hpp"
#include "diagnoses/clock_offset.hpp"
#include "diagnoses/dropped_requests.hpp"
#include "diagnoses/placeholder_identity.hpp"
#include "diagnoses/tracking_refused.hpp"
#include "top/catalog.hpp"

namespace topdump::diag {

// A frame's identifier as one integer, for the prefilter below.
constexpr std::uint32_t ident_key(const char* id) noexcept {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(id[0])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(id[1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(id[2])) << 16;
}

struct Watch {
  // Whether a frame of `ident` can matter to a detector: the identity
  // replies (top::is_identity_reply), TRC (top::refuses_tracking) and the
  // dated frames (top::carries_date), which decide; one switch per frame
  // instead of their string compares (diagnoses_test checks it covers them).
  static bool watched(const char* ident) noexcept {
    switch (ident_key(ident)) {
      case ident_key("PA2"):
      case ident_key("VSN"):
      case ident_key("VER"):
      case ident_key("TRC"):
      case ident_key("TIM"):
      case ident_key("UTC"):
        return true;
      default:
        return false;
    }
  }

  IdentityWatch identity;
  TrackingWatch tracking;
  ClockWatch clock;
  DroppedWatch dropped;
  BaudWatch baud;

  // A frame of the device (reply or push), its data and form.
  void device_frame(top::Dialect d, std::string_view ident, std::string_view data, std::uint64_t n,
                    std::int64_t ts, int dir) {
    identity.reply(d, ident, data, n, ts, dir);
    tracking.reply(d, ident, data, n, ts, dir);
  }
  // Any frame with a form: a date set on or reported by the camera.
  void dated_frame(const top::FormSpec* form, std::string_view ident, std::string_view data,
                   std::uint64_t n, std::int64_t ts, int dir) noexcept {
    if (form && top::carries_date(ident)) clock.frame(*form, data, ident, n, ts, dir);
  }
  // `frames`: whether the conversation carried any TOP frame.
  template <class Out>
  void verdicts(Out&& out, bool serial, bool frames) const {
    if (auto f = identity.verdict()) out(std::move(*f));
    if (auto f = clock.verdict()) out(std::move(*f));
    if (auto f = tracking.verdict()) out(std::move(*f));
    dropped.verdicts(out);
    if (serial && !frames)
      if (auto f = baud.verdict()) out(std::move(*f));
  }
};

}  // namespace topdump::diag
