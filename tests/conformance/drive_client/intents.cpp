#include "drive_client/intents.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

namespace drive {

namespace {

struct Named {
  const char* name;
  Intent::Do what;
};
constexpr Named kActions[] = {
    {"rate", Intent::Do::rate},           {"angle", Intent::Do::angle},
    {"stop", Intent::Do::stop},           {"centre", Intent::Do::centre},
    {"photo", Intent::Do::photo},         {"record", Intent::Do::record},
    {"zoom", Intent::Do::zoom},           {"track_point", Intent::Do::track_point},
    {"track_box", Intent::Do::track_box}, {"track_stop", Intent::Do::track_stop},
    {"identity", Intent::Do::identity},   {"clock", Intent::Do::clock},
    {"range", Intent::Do::range},         {"case", Intent::Do::case_start},
};

// A number at `key` (absent: `fallback`); throws the message on a wrong type.
double number(const nlohmann::json& j, const char* key, double fallback) {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_number() || !std::isfinite(it->get<double>()))
    throw std::string("\"") + key + "\" is not a finite number";
  return it->get<double>();
}

Intent one(const nlohmann::json& j) {
  if (!j.is_object()) throw std::string("not a JSON object");
  Intent in;
  const double t = number(j, "t", -1);
  if (t < 0 || t > 86400) throw std::string("\"t\" missing, negative or over a day");
  in.at_us = static_cast<std::uint64_t>(std::llround(t * 1e6));
  const auto d = j.find("do");
  if (d == j.end() || !d->is_string()) throw std::string("\"do\" missing or not a string");
  const std::string what = d->get<std::string>();
  const auto a = std::find_if(std::begin(kActions), std::end(kActions),
                              [&](const Named& n) { return what == n.name; });
  // Unknown actions are ignored (docs/DRIVE.md: later versions may add).
  in.what = a == std::end(kActions) ? Intent::Do::other : a->what;
  if (const auto f = j.find("frame"); f != j.end()) {
    if (!f->is_string() || (*f != "body" && *f != "earth"))
      throw std::string("\"frame\" is not \"body\" or \"earth\"");
    in.earth = *f == "earth";
  }
  const bool rate = in.what == Intent::Do::rate;
  in.pitch = number(j, rate ? "pitch_dps" : "pitch_deg", 0);
  in.yaw = number(j, rate ? "yaw_dps" : "yaw_deg", 0);
  in.roll = number(j, rate ? "roll_dps" : "roll_deg", 0);
  if (const auto o = j.find("on"); o != j.end()) {
    if (!o->is_boolean()) throw std::string("\"on\" is not true or false");
    in.on = o->get<bool>();
  }
  const double z = number(j, "rate", 0);
  if (in.what == Intent::Do::zoom && z != -1 && z != 0 && z != 1)
    throw std::string("\"rate\" of zoom is not -1, 0 or 1");
  in.zoom = static_cast<int>(z);
  in.x = number(j, "x", 0.5), in.y = number(j, "y", 0.5);
  in.w = number(j, "w", 0), in.h = number(j, "h", 0);
  if (in.what == Intent::Do::clock) {
    const auto u = j.find("utc");
    Utc cal{};
    if (u == j.end() || !u->is_string() || !parse_utc(u->get<std::string>(), cal))
      throw std::string("\"utc\" is not YYYY-MM-DDTHH:MM:SSZ");
    in.utc = u->get<std::string>();
  }
  return in;
}

}  // namespace

bool parse_utc(const std::string& s, Utc& o) {
  char z = 0;
  int n = 0;
  if (std::sscanf(s.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d%c%n", &o.year, &o.month, &o.day, &o.hour,
                  &o.minute, &o.second, &z, &n) != 7 ||
      z != 'Z' || static_cast<std::size_t>(n) != s.size())
    return false;
  return o.year >= 2000 && o.year <= 2099 && o.month >= 1 && o.month <= 12 && o.day >= 1 &&
         o.day <= 31 && o.hour <= 23 && o.minute <= 59 && o.second <= 60 && o.hour >= 0 &&
         o.minute >= 0 && o.second >= 0;
}

std::vector<Intent> parse_intents(const std::string& text, const std::string& name,
                                  std::string& error, std::size_t first_line) {
  std::vector<Intent> v;
  std::istringstream in(text);
  std::string line;
  for (std::size_t n = first_line; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto j = nlohmann::json::parse(line, nullptr, false);
    try {
      if (j.is_discarded()) throw std::string("not JSON");
      Intent i = one(j);
      i.line = n;
      v.push_back(std::move(i));
    } catch (const std::string& why) {
      error = name + ":" + std::to_string(n) + ": " + why;
      return {};
    }
  }
  std::stable_sort(v.begin(), v.end(),
                   [](const Intent& a, const Intent& b) { return a.at_us < b.at_us; });
  return v;
}

std::vector<Intent> load_intents(const std::string& path, std::string& error) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    error = path + ": cannot open the intents file";
    return {};
  }
  // At most 16 MiB: its size first, then that many bytes.
  constexpr std::streamoff kMax = 16 << 20;
  f.seekg(0, std::ios::end);
  const std::streamoff size = f.tellg();
  if (size < 0 || size > kMax) {
    error = path + (size < 0 ? ": cannot tell its size" : ": over 16 MiB, not an intents file");
    return {};
  }
  f.seekg(0);
  std::string text(static_cast<std::size_t>(size), '\0');
  f.read(text.data(), size);
  if (f.gcount() != size) {
    error = path + ": read error";
    return {};
  }
  return parse_intents(text, path, error);
}

bool IntentFile::poll(std::vector<Intent>& out, std::string& error) {
  std::ifstream f(path_, std::ios::binary);
  if (!f) return true;  // not there yet
  f.seekg(static_cast<std::streamoff>(offset_));
  char buf[65536];
  f.read(buf, sizeof buf);
  const auto n = static_cast<std::size_t>(f.gcount());
  if (f.bad()) {
    error = path_ + ": read error";
    return false;
  }
  offset_ += n;
  partial_.append(buf, n);
  const std::size_t end = partial_.rfind('\n');
  if (end == std::string::npos) {
    if (partial_.size() > sizeof buf) {
      error = path_ + ":" + std::to_string(line_) + ": a line over 64 KiB";
      return false;
    }
    return true;
  }
  const std::string lines = partial_.substr(0, end + 1);
  partial_.erase(0, end + 1);
  std::vector<Intent> v = parse_intents(lines, path_, error, line_);
  if (!error.empty()) return false;
  line_ += static_cast<std::size_t>(std::count(lines.begin(), lines.end(), '\n'));
  out.insert(out.end(), v.begin(), v.end());
  return true;
}

}  // namespace drive
