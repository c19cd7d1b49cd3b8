// What the checks of topconf drive read off a case's record (private to
// drive/): the driver's health over time, its beliefs against the truth,
// the wire's pushes and commands.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "drive/grade.hpp"

namespace topconf::drive::detail {

// "1.23 s"
std::string secs(double t);

// The times of the device's attitude reports (pushes and replies).
std::vector<double> attitude_times(const Record& r);
// The longest silence between attitude reports after `from` (the end of
// the case counts as one): its start and end (end == duration: it never resumed).
struct Gap {
  double from = 0, to = 0;
  double length() const { return to - from; }
};
std::optional<Gap> longest_gap(const Record& r, double from = 0);
// Whether a frame of the driver commands a non-zero rate on some axis.
bool moving(const WireFrame& w);
// The driver's frames that turn an axis, in (from, to].
int moving_frames(const Record& r, double from, double to);
// Whether it stops every axis it names (a zero rate, a PTZ stop).
bool stopping(const WireFrame& w);
// The time of the first intent `what`, or nullopt.
std::optional<double> intent_at(const Record& r, std::string_view what);

// The driver's health as its beliefs said at `t`: nullopt before any said.
std::optional<bool> healthy_at(const Record& r, double t);
// Whether some belief in (from, to] says unhealthy (healthy:false).
bool unhealthy_in(const Record& r, double from, double to);
// Whether some belief in (from, to] is healthy with an attitude.
bool healthy_in(const Record& r, double from, double to);
// The truth sample nearest `t`.
const Truth* truth_at(const Record& r, double t);

// "belief within 2 deg of the truth, or unhealthy" for the beliefs after
// `from`: ok, fail with the first belief off, or unimplemented (no belief
// of the attitude or health).
struct BeliefCheck {
  Grade grade = Grade::pass;
  Check check;
};
BeliefCheck beliefs_follow_truth(const Record& r, double from);

// The last value of belief `key` (a string, "unknown" for null).
std::optional<std::string> last_belief(const Record& r, const char* key);
// Whether the driver's text for the version (or model) is the device's:
// the same text, its numbers ("1.6.26" for "1.6.26.R.D", "123" or "1.2.3"
// for "123", "2" for "V2"), or trailing zero parts ("1.0.0" for "1").
bool same_identity(std::string_view belief, std::string_view device, bool version);

// A verdict under construction: each check lowers the grade to its own
// when worse (pass < non-strict, informational < unimplemented < fail).
struct Judge {
  Verdict v;
  void add(Grade g, std::string name, bool ok, std::string detail);
  void pass(std::string name, std::string detail) {
    add(Grade::pass, std::move(name), true, std::move(detail));
  }
  void fail(std::string name, std::string detail) {
    add(Grade::fail, std::move(name), false, std::move(detail));
  }
  // beliefs_follow_truth as a check.
  void beliefs(const Record& r, double from);
};

// The checks of sections 3 to 9 (grade_other.cpp).
void grade_other(Judge& j, const CaseSpec& c, top::Model model, topsim::TransportKind link,
                 const Record& r);

// The most frames of `ident` the driver sent within any one second.
int most_per_second(const Record& r, std::string_view ident);

}  // namespace topconf::drive::detail
