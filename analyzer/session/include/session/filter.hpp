// The command line's selection of frames and findings (--ident, --addr,
// --severity, --from/--to, --finding, --mute, -c).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "findings/afindings.hpp"
#include "session/events.hpp"

namespace topdump {

// The command line's selection. It applies to everything reported alike:
// frames, garbage, findings (session notes about a request or stream), the
// statistics and the exit status; pairing and timeouts still see every
// frame. Findings about the capture file itself (no conversation) are kept
// whatever the identifier, address and time selection.
struct Filter {
  std::vector<std::string> idents;  // empty: all (matched case-insensitively)
  std::vector<std::string> addrs;   // TOP address letters or network hosts
  top::Severity min_severity = top::Severity::info;
  bool severity_set = false;
  std::int64_t from = kNoTime, to = kNoTime;
  // --from +1.5s: microseconds after the first timestamp of the input,
  // resolved into from/to when the analyzer sees it.
  std::int64_t from_rel = kNoTime, to_rel = kNoTime;
  // --finding: only frames and events that carry one of these codes.
  std::vector<top::FindingCode> findings;
  std::vector<ACode> afindings;
  // --mute: these findings are dropped wherever they appear (not shown, not
  // counted, not in the exit status).
  std::vector<top::FindingCode> mute;
  std::vector<ACode> amute;
  // -c: the input ends after this many selected frames (0: no limit).
  std::uint64_t max_frames = 0;

  bool selects(const FrameEvent& e) const;
  bool selects(const NoteEvent& e) const;
  bool selects(const GarbageEvent& e) const;
  bool selects_time(std::int64_t ts) const;
  bool selects_ident(std::string_view ident) const;
  bool mutes(top::FindingCode c) const {
    return !mute.empty() && std::find(mute.begin(), mute.end(), c) != mute.end();
  }
  bool mutes(ACode c) const {
    return !amute.empty() && std::find(amute.begin(), amute.end(), c) != amute.end();
  }
  bool active() const;
  // Resolves relative times against the input's first timestamp.
  void start_at(std::int64_t first);
  // Parses a code for --finding/--mute (a frame, catalog or analyzer code);
  // false when there is none of that name.
  bool add_code(std::string_view name, bool muted);
};

// "1.5", "1.5s", "200ms", "250us": a duration in microseconds (relative
// --from/--to); nullopt when it is none of these or negative.
std::optional<std::int64_t> parse_duration(std::string_view s);

}  // namespace topdump
