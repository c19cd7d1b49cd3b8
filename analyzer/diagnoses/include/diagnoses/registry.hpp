// Every detector of analyzer/diagnoses/, registered against the diagnoses
// table (top/diagnoses.hpp, TOP_DIAGNOSES): each detector names the codes
// it decides (its `codes`), and registry.cpp checks, row by row of the
// table, that exactly one registered detector decides each. Adding a
// diagnosis is one table row, one detector file listed here, its test and
// its capture; a row without its detector does not compile.
//
// Who feeds them: the session, as the capture streams by. Per
// conversation, the Watch (watch.hpp: identity, tracking, clock, dropped
// requests, baud, the motion track's four and refresh-gap) and the silent
// stretch (session.hpp, Silence); per stream, the stall and never-started
// watches (session/stats.hpp, StreamStat) and, at the stream's end,
// StreamRate.
#pragma once

#include <algorithm>
#include <tuple>

#include "diagnoses/attitude_stale.hpp"
#include "diagnoses/axis_left_moving.hpp"
#include "diagnoses/baud_mismatch.hpp"
#include "diagnoses/clock_offset.hpp"
#include "diagnoses/command_ignored.hpp"
#include "diagnoses/direction_inverted.hpp"
#include "diagnoses/dropped_requests.hpp"
#include "diagnoses/placeholder_identity.hpp"
#include "diagnoses/refresh_gap.hpp"
#include "diagnoses/silent_device.hpp"
#include "diagnoses/stream_never_started.hpp"
#include "diagnoses/stream_rate.hpp"
#include "diagnoses/stream_stalled.hpp"
#include "diagnoses/tracking_refused.hpp"

namespace topdump::diag {

using Detectors = std::tuple<SilentStretch, DroppedWatch, StreamRate, StallWatch, NeverStartedWatch,
                             DirectionWatch, IgnoredWatch, StaleWatch, LeftMovingWatch,
                             IdentityWatch, ClockWatch, TrackingWatch, BaudWatch, RefreshWatch>;

// How many registered detectors decide diagnosis `d`.
template <class... D>
constexpr std::size_t deciders(top::Diagnosis d, const std::tuple<D...>* = nullptr) noexcept {
  return (static_cast<std::size_t>(std::count(D::codes.begin(), D::codes.end(), d)) + ...);
}
constexpr std::size_t deciders_of(top::Diagnosis d) noexcept {
  return deciders(d, static_cast<const Detectors*>(nullptr));
}

}  // namespace topdump::diag
