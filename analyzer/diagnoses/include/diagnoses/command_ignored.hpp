// command-ignored: angle commands acknowledged (echoed) while the gimbal did
// not move toward their target, when other commands did move it: firmware
// that echoes a command it does not carry out. A window counts when its
// target was kMinStep deg or more away, at least kMinSeconds of attitude
// followed, and the axis moved less than kStill deg.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"
#include "diagnoses/judged.hpp"

namespace topdump::diag {

class IgnoredWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::command_ignored};
  static constexpr double kMinStep = 3.0, kStill = 0.5, kMinSeconds = 1.0, kMoving = 2.0;
  void window(const Judged& j);
  template <class Out>
  void verdicts(Out&& out) const {
    for (const Entry& e : ignored_)
      if (e.spec)
        if (auto f = verdict(e)) out(std::move(*f));
  }

 private:
  struct Entry {
    const top::MotionSpec* spec = nullptr;
    Case c;
    Judged first;
  };
  std::optional<Found> verdict(const Entry& e) const;
  std::array<Entry, 4> ignored_{};                  // the first identifiers ignored
  std::array<const top::MotionSpec*, 4> movers_{};  // identifiers that moved the gimbal
};

}  // namespace topdump::diag
