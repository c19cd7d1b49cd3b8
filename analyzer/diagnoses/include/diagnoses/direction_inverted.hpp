// direction-inverted: angle or rate commands on an axis move the gimbal
// opposite to their sign. Judged per axis and kind (angle, rate, PTZ) over
// the windows the motion track closes: a window votes when the gimbal moved
// at least kMinMoved deg (angles: toward a target kMinStep deg or more away
// whose mirror, the other convention's -target, lies on the other side);
// the verdict needs the inverted votes to outnumber the right ones twice.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"
#include "diagnoses/judged.hpp"

namespace topdump::diag {

class DirectionWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::direction_inverted};
  static constexpr double kMinMoved = 1.5, kMinStep = 3.0;
  void window(const Judged& j);
  template <class Out>
  void verdicts(Out&& out) const {
    for (std::size_t i = 0; i < slots_.size(); ++i)
      if (auto f = verdict(i)) out(std::move(*f));
  }

 private:
  struct Slot {
    std::uint32_t right = 0, inverted = 0;
    Case c;
    Judged first;  // the first inverted window
  };
  std::optional<Found> verdict(std::size_t i) const;
  std::array<Slot, top::axis_count * 3> slots_{};  // axis x kind (angle, rate, PTZ)
};

}  // namespace topdump::diag
