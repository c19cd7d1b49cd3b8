// The intents file of `topconf drive` (TOPCONF_INTENT, docs/DRIVE.md): JSON
// Lines of timed actions the driver is asked to perform, read into Intents
// with an error naming the file, line and key of anything it cannot take.
#pragma once

#include <cstdint>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

namespace drive {

struct Intent {
  enum class Do : std::uint8_t {
    rate,
    angle,
    stop,
    centre,
    photo,
    record,
    zoom,
    track_point,
    track_box,
    track_stop,
    identity,
    clock,
    range,
    case_start,  // --persistent: the next case starts (the device changed in place)
    other        // an action this client does not know (later ones): ignored
  };
  std::uint64_t at_us = 0;  // after the driver started
  Do what = Do::stop;
  bool earth = false;                   // frame: earth (else body)
  double pitch = 0, yaw = 0, roll = 0;  // deg/s (rate) or deg (angle)
  bool on = false;                      // record
  int zoom = 0;                         // -1, 0, 1
  double x = 0, y = 0, w = 0, h = 0;    // track_point, track_box: 0..1 of the image
  std::string utc;                      // clock: "2026-12-06T12:00:00Z"
  std::size_t line = 0;                 // in the file, from 1
};

// The intents of `path`, sorted by time (stable). On an error, `error` says
// "PATH:LINE: ..." and the result is empty.
std::vector<Intent> load_intents(const std::string& path, std::string& error);
// The same for the text of a file (`name` in the errors; `first_line`: the
// number of its first line).
std::vector<Intent> parse_intents(const std::string& text, const std::string& name,
                                  std::string& error, std::size_t first_line = 1);

// An intents file followed as it grows (`tail -f`: topconf drive
// --persistent appends each case's intents while the driver runs).
class IntentFile {
 public:
  explicit IntentFile(std::string path) : path_(std::move(path)) {}
  // The intents of the complete lines added since the last call (sorted).
  // False with `error` set on a bad line, an unreadable file, or a line over
  // 64 KiB; a file not there yet is no error.
  bool poll(std::vector<Intent>& out, std::string& error);

 private:
  std::string path_, partial_;
  std::uint64_t offset_ = 0;
  std::size_t line_ = 1;
};

// The calendar of a clock intent's "YYYY-MM-DDTHH:MM:SSZ": false when it is
// not one.
struct Utc {
  int year, month, day, hour, minute, second;  // month 1-12
};
bool parse_utc(const std::string& s, Utc& out);
inline std::tm to_tm(const Utc& u) {
  std::tm t{};
  t.tm_year = u.year - 1900, t.tm_mon = u.month - 1, t.tm_mday = u.day;
  t.tm_hour = u.hour, t.tm_min = u.minute, t.tm_sec = u.second;
  return t;
}

}  // namespace drive
