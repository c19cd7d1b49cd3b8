// What one case of topconf drive saw (docs/DRIVE.md): the intents it
// gave, the frames on the wire, the device's truth over time and the
// driver's beliefs, each stamped with seconds since the driver started.
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace topconf::drive {

// One action the driver is asked to perform (an intents file line).
struct Intent {
  double t = 0;         // seconds after the driver starts
  nlohmann::json line;  // the whole line ("do" and its fields, "t" included)
  std::string what() const { return line.value("do", ""); }
};

// A frame on the wire, decoded as far as the checks need.
struct WireFrame {
  double t = 0;
  bool from_driver = false;  // a request of the driver (else the device sent it)
  bool ok = false;           // parsed with a good checksum
  char src = 0, dst = 0, control = 0;
  std::string ident, data, raw;
  // A motion command of the driver: a rate (per axis, deg/s in the
  // convention of docs/DRIVE.md: right and up positive), a PTZ turn or stop,
  // an angle target.
  bool rate = false, angle = false;
  std::array<bool, 3> axis{};     // the axes the command names
  std::array<double, 3> value{};  // rate (deg/s) or angle (deg) per axis
  // A stream switch turned on by the driver (GIA 01, GAA nn).
  bool stream_on = false;
  // An attitude push or reply of the device (GIA, GAC, GIC).
  bool attitude = false;
};

// The device's truth at one time (Device::yaw/pitch/roll: right and up
// positive), and whether it pushed an attitude stream then.
struct Truth {
  double t = 0;
  std::array<double, 3> angle{};  // yaw, pitch, roll
  std::array<double, 3> rate{};   // commanded rates in force
  std::array<double, 3> limit_min{}, limit_max{};
  int streams_on = 0;
};

// One belief line, stamped when topconf read it.
struct Belief {
  double t = 0;
  nlohmann::json line;
};

struct Record {
  std::vector<Intent> intents;
  std::vector<WireFrame> wire;
  std::vector<Truth> truth;
  std::vector<Belief> beliefs;
  std::size_t non_json_lines = 0;
  std::vector<std::string> errors;  // the beliefs' "error" texts
  double duration_s = 0;            // the case's length
  double reboot_at = -1;            // when the device power-cycled (reboot=), -1: never
  std::string version, model;       // what the device answers for its identity
  double range_m = 0;               // what its rangefinder measures
};

}  // namespace topconf::drive
