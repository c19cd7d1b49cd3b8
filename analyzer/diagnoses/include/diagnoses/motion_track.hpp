// The motion diagnoses' common state for one conversation: the latest
// attitude report of each reference frame, kept as a copy of its raw data
// (read only when a window is judged), and per axis the open command
// window: from a command to the next command of another value on that axis.
// A rate refreshed with the same data, or a new angle target within
// kMinWindow of the window's start, keeps the window open; a window is
// judged (its command and the two attitude reports read) only when it
// closes after kMinWindow of attitude, so a capture's commands cost a byte
// compare each and its attitude reports a copy of a few bytes.
#pragma once

#include <array>
#include <cstring>

#include "diagnoses/attitude_stale.hpp"
#include "diagnoses/axis_left_moving.hpp"
#include "diagnoses/command_ignored.hpp"
#include "diagnoses/direction_inverted.hpp"
#include "diagnoses/refresh_gap.hpp"

namespace topdump::diag {

// Yaw unwrapped across the turns: the motion track reads the yaw of an
// attitude report about every kMinWindow (its marks) and adds each step the
// short way round, so a window or a capture's tail that turns past 180 deg
// is measured whole. `epoch` 0: none; two readings compare only within one.
struct Unwrap {
  std::uint32_t epoch = 0;
  float turned = 0;  // the last mark's yaw, unwrapped (floats: a Snap stays
  float yaw = 0;     // within a cache line), and as reported
};

// A copy of a motion frame's data (at most 16 chars: every motion form),
// in 56 bytes: the session copies one for most motion frames.
struct Snap {
  const top::MotionSpec* spec = nullptr;  // none yet
  const top::FormSpec* form = nullptr;
  std::int64_t ts = kNoTime;
  std::uint64_t w[2] = {0, 0};  // the data (words())
  Unwrap u;                     // attitude: the unwrapping when it came
  std::uint8_t len = 0;
  bool set() const noexcept { return spec != nullptr; }
  std::string_view view() const noexcept { return {reinterpret_cast<const char*>(w), len}; }
  bool take(const top::MotionSpec& m, const top::FormSpec* f, std::string_view d,
            std::int64_t t) noexcept {
    if (!f || d.size() > sizeof w) return false;
    spec = &m, form = f, ts = t, len = static_cast<std::uint8_t>(d.size());
    words(d, w);
    return true;
  }
  // Whether `d` of `m` is this data: two word compares.
  bool same(const top::MotionSpec& m, std::string_view d) const noexcept {
    if (spec != &m || d.size() != len) return false;
    std::uint64_t o[2];
    words(d, o);
    return ((o[0] ^ w[0]) | (o[1] ^ w[1])) == 0;
  }
  // The data as two little-endian words, zero-padded, by fixed-size loads
  // that stay within `d` (two that overlap for a length between two sizes:
  // 2-3 chars as 16-bit loads, 4-8 as 32-bit, 9-16 as 64-bit).
  static void words(std::string_view d, std::uint64_t (&out)[2]) noexcept {
    const std::size_t k = d.size();
    const char* p = d.data();
    out[1] = 0;
    if (k > 8) {
      std::memcpy(&out[0], p, 8);
      std::memcpy(&out[1], p + k - 8, 8);  // overlaps the first below 16
      out[1] >>= 8 * (16 - k);             // keeps chars 8 to k - 1
    } else if (k >= 4) {
      std::uint32_t a, b;
      std::memcpy(&a, p, 4);
      std::memcpy(&b, p + k - 4, 4);  // chars k - 4 to k - 1, overlapping a's
      out[0] = a | std::uint64_t{b} << 8 * (k - 4);
    } else if (k >= 2) {
      std::uint16_t a, b;
      std::memcpy(&a, p, 2);
      std::memcpy(&b, p + k - 2, 2);
      out[0] = a | std::uint64_t{b} << 8 * (k - 2);
    } else {
      out[0] = k ? static_cast<unsigned char>(p[0]) : 0;
    }
  }
  // An attitude report's angle on `axis`, up and right positive.
  bool angle(int axis, double& out) const noexcept;
  // The yaw turned from `a` to `b` (their angles `ya`, `yb`) across whole
  // turns; false when they are not of one unwrapping.
  static bool turned(const Snap& a, double ya, const Snap& b, double yb, double& out) noexcept;
};

static_assert(sizeof(Snap) <= 56, "a Snap fits a cache line with room to spare");

class MotionTrack {
 public:
  static constexpr std::int64_t kMinWindow = 500'000;  // us
  static constexpr std::int64_t kSample = 20'000;  // us: attitude kept at most 50 times a second
  static constexpr std::int64_t kStaleUs = top::attitude_stale_ms * 1000;

  // A frame of a motion identifier with a good checksum: `request` from the
  // client, else the device's.
  // `model`: the one topdump was told (--model), or unknown.
  void frame(const top::MotionSpec& m, const top::FormSpec* form, bool request, char control,
             std::string_view data, std::uint64_t n, std::int64_t ts, int dir, top::Model model);
  // The model the device named (SkyDroid MOD). It chooses the speed-refresh
  // limit when topdump was not told one, as it may only lift that limit (a
  // C13 records none); a sign trait needs the model told (--model): a named
  // model must not turn a capture's directions.
  void named(top::Model m) noexcept {
    if (m != named_) refresh_limit_us_ = -1;  // looked up again
    named_ = m;
  }
  // The camera's tracker drives the gimbal (top::reports_tracking): the
  // open windows are judged up to now and closed, and no command opens one
  // until the tracker lets go (released(), top::releases_tracking): the
  // tracker's motion answers no command, and ArduPilot's Topotek driver
  // sends none while its camera tracks (AP_Mount_Topotek::update, PR #27568).
  void handover();
  void released() noexcept { tracking_ = false; }
  // The conversation ended at `end_ts` (its last frame): judge the open
  // windows.
  void finish(std::int64_t end_ts);
  template <class Out>
  void verdicts(Out&& out) const {
    direction_.verdicts(out);
    ignored_.verdicts(out);
    if (auto f = stale_.verdict()) out(std::move(*f));
    left_.verdicts(out);
    if (auto f = refresh_.verdict()) out(std::move(*f));
  }

 private:
  struct Window {
    Snap cmd;             // its latest command (cmd.spec null: none open)
    int ref = 0;          // the attitude it is judged against (0 body, 1 earth)
    Snap start, at_last;  // the attitude when it opened, and at its latest command
    std::int64_t open_ts = kNoTime, last_ts = kNoTime;
    std::uint64_t first_n = 0, last_n = 0, commands = 0;
    int dir = 0, sign = 0;  // rates and PTZ: the raw direction commanded
    bool acked = false;
  };
  void command(const top::MotionSpec& m, const top::FormSpec* form, std::string_view data,
               std::uint64_t n, std::int64_t ts, int dir);
  void on_axis(int axis, int sign, const top::MotionSpec& m, const top::FormSpec* form,
               std::string_view data, std::uint64_t n, std::int64_t ts, int dir);
  void attitude(const top::MotionSpec& m, const top::FormSpec* form, std::string_view data,
                std::int64_t ts);
  // A new mark of the attitude `slot`: its yaw read, the unwrapping on.
  // (cold, as judge: about twice a second, not per frame; compiled for
  // size and kept out of the per-frame code: docs/perf/decisions.md)
  [[gnu::cold]] void mark(std::size_t slot);
  // Judges the window `w` if it can be (its command and the attitude read
  // only then); the caller clears it.
  void close(const Window& w) {
    if (judgeable(w)) judge(w);
  }
  // judged on reports of one attitude, fresh when it opened, over kMinWindow
  bool judgeable(const Window& w) const noexcept {
    const Snap& end = att_[static_cast<std::size_t>(w.ref)];
    return w.cmd.spec && w.start.set() && end.spec == w.start.spec && end.ts >= w.open_ts &&
           end.ts - w.start.ts >= kMinWindow && w.open_ts - w.start.ts <= kStaleUs;
  }
  [[gnu::cold]] void judge(const Window& w);
  // The window's command, axis and sender, and the attitude it is judged
  // against (which has a report).
  WindowOf window_of(const Window& w) const noexcept;
  // refresh-gap: whether the rate window `w` went unrefreshed until `ts`.
  void check_refresh(const Window& w, std::int64_t ts);
  int ref_for(const top::MotionSpec& m) const noexcept;

  std::array<Snap, 2> att_{};                   // the latest report: body, earth
  std::array<std::array<Snap, 2>, 2> marks_{};  // per frame: reports about 0.5 s apart
  // Per frame, when a kept report last differed from the one before it in
  // any byte: an attitude that reads the same to the end has stopped.
  std::array<std::int64_t, 2> changed_{kNoTime, kNoTime};
  // Reports that read the same for this long at the end: the gimbal stopped.
  static constexpr std::int64_t kStoppedUs = 200'000;
  std::array<Unwrap, 2> unwrap_{};  // per frame: yaw across the marks
  std::uint32_t epochs_ = 0;
  std::uint64_t reports_ = 0;
  std::int64_t last_report_ = kNoTime;
  const top::MotionSpec* last_attitude_ = nullptr;
  top::Model model_ = top::Model::unknown;  // told (--model)
  top::Model named_ = top::Model::unknown;  // named by the device
  std::array<Window, top::axis_count> win_{};
  DirectionWatch direction_;
  IgnoredWatch ignored_;
  StaleWatch stale_;
  LeftMovingWatch left_;
  RefreshWatch refresh_;
  std::int64_t refresh_limit_us_ = -1;  // -1: not looked up yet; 0: no limit applies
  bool tracking_ = false;               // the camera's tracker drives the gimbal
};

// Inline: the session calls it for every motion frame, most of them
// attitude reports.
inline void MotionTrack::frame(const top::MotionSpec& m, const top::FormSpec* form, bool request,
                               char control, std::string_view data, std::uint64_t n,
                               std::int64_t ts, int dir, top::Model model) {
  if (ts == kNoTime) return;
  model_ = model;
  if (m.kind == top::MotionKind::attitude) {
    // a report: a push or the answer to a read (the Topotek GIA switch's
    // echo, a write, carries no angles)
    if (!request && control == 'r') attitude(m, form, data, ts);
    return;
  }
  if (control != 'w') return;
  if (request) {
    if (!tracking_) command(m, form, data, n, ts, dir);
    return;
  }
  // the device's echo acknowledges the window of its identifier: one on
  // each of its axes (a PTZ's on the axis its action turned)
  if (m.kind == top::MotionKind::ptz) {
    for (Window& w : win_)
      if (w.cmd.spec == &m) w.acked = true;
    return;
  }
  for (const top::MotionAxis& a : m.fields())
    if (Window& w = win_[static_cast<std::size_t>(a.axis)]; w.cmd.spec == &m) w.acked = true;
}

inline void MotionTrack::attitude(const top::MotionSpec& m, const top::FormSpec* form,
                                  std::string_view data, std::int64_t ts) {
  const std::size_t slot = m.reference == top::Reference::earth ? 1 : 0;
  // A window is judged over half a second or more: a report within kSample
  // of the one kept (of the same attitude) is counted, not copied.
  Snap& a = att_[slot];
  if (a.spec != &m || ts - a.ts >= kSample || ts < a.ts) {
    if (!a.same(m, data)) changed_[slot] = ts;
    if (!a.take(m, form, data, ts)) return;
    a.u = unwrap_[slot];
  } else if (!form || data.size() > sizeof a.w) {
    return;
  }
  ++reports_;
  last_report_ = ts;
  last_attitude_ = &m;
  auto& mk = marks_[slot];
  if (!mk[1].set() || ts - mk[1].ts >= kMinWindow) {
    mk[0] = mk[1];
    mk[1] = a;
    mark(slot);
  }
}

}  // namespace topdump::diag
