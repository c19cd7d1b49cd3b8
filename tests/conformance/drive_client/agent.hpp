// An intent of `topconf drive` handed to a driver-like client as the
// driver's API call it stands for (the one mapping, shared by
// topkit_drive_client and the in-process tests of drive_client_test.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "drive_client/intents.hpp"

namespace drive {

// Acts on `i` at `now_us`; false when the client has no such call (the
// SkyDroid driver has no tracking): the intent is not acted on.
template <class Client>
bool act(Client& c, const Intent& i, std::uint64_t now_us) {
  using D = Intent::Do;
  switch (i.what) {
    case D::rate:
      c.rate(i.yaw, i.pitch, i.roll, i.earth);
      return true;
    case D::angle:
      c.angle(i.yaw, i.pitch, i.roll, i.earth);
      return true;
    case D::stop:
      c.stop();
      return true;
    case D::centre:
      c.centre();
      return true;
    case D::photo:
      c.photo();
      return true;
    case D::record:
      c.record(i.on);
      return true;
    case D::zoom:
      c.zoom(i.zoom);
      return true;
    case D::identity:
      c.ask_identity();
      return true;
    case D::clock: {
      Utc u{};
      if (!parse_utc(i.utc, u)) return false;
      c.set_clock(u, now_us);
      return true;
    }
    case D::range:
      if constexpr (requires { c.measure_range(); }) {
        c.measure_range();
        return true;
      }
      return false;
    case D::case_start:
      // What the driver learnt of the device is of the last case's device.
      c.forget();
      return true;
    case D::other:
      return true;  // not an action for a driver (ignored)
    case D::track_point:
    case D::track_box:
    case D::track_stop:
      if constexpr (requires { c.track_point(0.0, 0.0); }) {
        if (i.what == D::track_point) c.track_point(i.x, i.y);
        if (i.what == D::track_box) c.track_box(i.x, i.y, i.w, i.h);
        if (i.what == D::track_stop) c.track_stop();
        return true;
      }
      return false;
  }
  return false;
}

// The intents of a run, handed out as their time comes.
class Script {
 public:
  explicit Script(std::vector<Intent> v) : v_(std::move(v)) {}
  // More intents (a followed file): those not yet due keep their order.
  void add(const std::vector<Intent>& more) {
    v_.insert(v_.end(), more.begin(), more.end());
    std::stable_sort(v_.begin() + static_cast<std::ptrdiff_t>(next_), v_.end(),
                     [](const Intent& a, const Intent& b) { return a.at_us < b.at_us; });
  }
  // Acts on every intent due by `t_us` after the start; returns how many
  // were not acted on.
  template <class Client>
  int run_due(Client& c, std::uint64_t t_us, std::uint64_t now_us) {
    int skipped = 0;
    for (; next_ < v_.size() && v_[next_].at_us <= t_us; ++next_)
      if (!act(c, v_[next_], now_us)) ++skipped;
    return skipped;
  }
  // When the next intent is due (after the start), or UINT64_MAX.
  std::uint64_t next_at() const { return next_ < v_.size() ? v_[next_].at_us : UINT64_MAX; }

 private:
  std::vector<Intent> v_;
  std::size_t next_ = 0;
};

}  // namespace drive
