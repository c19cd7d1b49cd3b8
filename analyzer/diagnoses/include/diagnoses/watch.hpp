// The detectors of one conversation, in one place: the session holds one
// Watch per conversation (and a StallWatch and NeverStartedWatch per
// stream, session/stats.hpp) and hands it the frames it already decoded;
// at the conversation's end verdicts() yields what was found. Every
// detector registered here has its row in top/diagnoses.hpp; its state is
// a few numbers, whatever the capture's length.
#pragma once

#include <memory>

#include "diagnoses/baud_mismatch.hpp"
#include "diagnoses/clock_offset.hpp"
#include "diagnoses/dropped_requests.hpp"
#include "diagnoses/motion_track.hpp"
#include "diagnoses/placeholder_identity.hpp"
#include "diagnoses/tracking_refused.hpp"
#include "top/catalog.hpp"
#include "top/device.hpp"
#include "top/diagnoses.hpp"

namespace topdump::diag {

// The session hands device_frame and dated_frame only the frames whose
// identifier may matter to them (the rules' prefilter,
// top/detail/prefilter.hpp), and the motion track the motion frames.
struct Watch {
  IdentityWatch identity;
  TrackingWatch tracking;
  ClockWatch clock;
  DroppedWatch dropped;
  BaudWatch baud;
  // direction-inverted, command-ignored, attitude-stale, axis-left-moving,
  // refresh-gap: made at the conversation's first motion frame (or model
  // name or tracker handover), as most conversations have none and it is
  // 4 KB to zero (docs/perf/fuzz-speed.md, "Issue 48: the per-conversation
  // cost"); until then it would judge nothing.
  MotionTrack& motion() {
    if (!motion_) motion_ = std::make_unique<MotionTrack>();
    return *motion_;
  }
  // The conversation ended at `end_ts`: the motion track judges its open
  // windows.
  void finish(std::int64_t end_ts) {
    if (motion_) motion_->finish(end_ts);
  }
  // A frame of the device (reply or push), its data and form.
  void device_frame(top::Dialect d, std::string_view ident, char control, std::string_view data,
                    std::uint64_t n, std::int64_t ts, int dir) {
    identity.reply(d, ident, data, n, ts, dir);
    tracking.reply(d, ident, data, n, ts, dir);
    if (const top::Model m = top::model_named_by(d, ident, data); m != top::Model::unknown)
      motion().named(m);
    if (top::reports_tracking(d, ident, control, data))
      motion().handover();
    else if (motion_ && top::releases_tracking(d, ident, control, data))
      motion_->released();  // (a track not made yet has no tracker to release)
  }
  // Any frame with a form: a date set on or reported by the camera.
  void dated_frame(const top::FormSpec* form, std::string_view ident, std::string_view data,
                   std::uint64_t n, std::int64_t ts, int dir, bool device) noexcept {
    if (form && top::carries_date(ident)) clock.frame(*form, data, ident, n, ts, dir, device);
  }
  // `frames`: whether the conversation carried any TOP frame.
  template <class Out>
  void verdicts(Out&& out, bool serial, bool frames) const {
    if (auto f = identity.verdict()) out(std::move(*f));
    if (auto f = clock.verdict()) out(std::move(*f));
    if (auto f = tracking.verdict()) out(std::move(*f));
    dropped.verdicts(out);
    if (motion_) motion_->verdicts(out);
    if (serial && !frames)
      if (auto f = baud.verdict()) out(std::move(*f));
  }

 private:
  std::unique_ptr<MotionTrack> motion_;
};

}  // namespace topdump::diag
