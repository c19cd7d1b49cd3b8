// Well-behaved clients for the diagnosis faults' tests (fault_diagnoses_test.cpp):
// each does what a healthy field client does (ArduPilot's drivers as
// docs/sources/ardupilot.md sections 1 and 2 record them), so that topsim's
// recording of a run without faults names no diagnosis, and a run with one
// fault names the diagnosis the fault shows. And topdump's reading of a
// recording, frame by frame.
#pragma once

#include <sys/wait.h>

#include <cstdint>
#include <cstdio>
#include <ctime>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "driver_harness.hpp"
#include "top/frame.hpp"
#include "topotek_client.hpp"

namespace faultclients {

inline std::string build(char src, top::Header h, char dst, char control, std::string_view ident,
                         std::string_view data) {
  return top::build_frame(
      {.header = h, .src = src, .dst = dst, .control = control, .ident = ident, .data = data});
}

// The time now as SkyDroid TIM (hhmmss.ssDDMMYY, SkyDroid 4.6) or Topotek UTC
// (HHMMSSDDMMYY, 5.10), the month 1-based.
inline std::string date_now(bool skydroid) {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char b[40];
  std::snprintf(b, sizeof b, skydroid ? "%02d%02d%02d.00%02d%02d%02d" : "%02d%02d%02d%02d%02d%02d",
                tm.tm_hour, tm.tm_min, tm.tm_sec, tm.tm_mday, tm.tm_mon + 1, tm.tm_year % 100);
  return b;
}

// SkyDroid, as ArduPilot's SkyDroid driver does it (section 2), in short:
// the attitude push asked at 10 Hz once a second (GAA 0A), VER and MOD read
// once a second until answered, the time set once (TIM, 1-based month), a
// pitch rate of +10 deg/s (GSP 14) refreshed every 50 ms from 0.5 s to
// 1.5 s and then stopped (three GSP 00), a yaw angle of 10 deg (GAY) at
// 1.8 s where the model takes GAY (`angles`; no evidence puts GAY on a C13:
// its driver sends rates only).
class SkyClient : public DriverClient {
 public:
  explicit SkyClient(bool angles = true) : angles_(angles) {}
  static constexpr std::uint64_t kRateFrom = 500000, kRateTo = 1500000, kYawAt = 1800000;
  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    if (start_ == 0) start_ = now_us;
    const std::uint64_t t = now_us - start_;
    if (t >= next_1hz_) {
      next_1hz_ += 1000000;
      out.push_back(f(top::Header::fixed, 'G', 'w', "GAA", "0A"));
      if (!version) out.push_back(f(top::Header::fixed, 'D', 'r', "VER", "00"));
      if (!model) out.push_back(f(top::Header::fixed, 'D', 'r', "MOD", "00"));
    }
    if (!time_sent_ && t >= 300000) {
      out.push_back(f(top::Header::variable, 'D', 'w', "TIM", date_now(true)));
      time_sent_ = true;
    }
    if (t >= kRateFrom && t < kRateTo) {
      out.push_back(f(top::Header::fixed, 'G', 'w', "GSP", "14"));
    } else if (t >= kRateTo && stops_ < 3) {
      out.push_back(f(top::Header::fixed, 'G', 'w', "GSP", "00"));
      ++stops_;
    }
    if (angles_ && !yaw_sent_ && t >= kYawAt) {
      out.push_back(f(top::Header::variable, 'G', 'w', "GAY", "03E863"));  // 10.00 deg at 9.9 deg/s
      yaw_sent_ = true;
    }
    return now_us + 50000;
  }
  void on_frame(const top::Frame& fr, std::uint64_t) override {
    if (!fr.ok()) return;
    if (fr.ident_view() == "VER") version = true;
    if (fr.ident_view() == "MOD") model = true;
  }
  bool version = false, model = false;

 private:
  std::string f(top::Header h, char dst, char control, std::string_view id,
                std::string_view data) const {
    return build(client, h, dst, control, id, data);
  }
  bool angles_;
  std::uint64_t start_ = 0, next_1hz_ = 0;
  bool time_sent_ = false, yaw_sent_ = false;
  int stops_ = 0;
};

// Topotek, as ArduPilot's Topotek driver does it (topotek_client.hpp): from
// 0.5 s to 1.5 s a pitch rate of +10 deg/s (YPR), then stopped (PTZ 00);
// from 1.8 s angle targets yaw 10, pitch 10 (GAY, GIP); tracking at the
// image centre from 2.5 s (TRC 02, LOC).
class TopoClient : public TopotekClient {
 public:
  static constexpr std::uint64_t kRateFrom = 500000, kRateTo = 1500000, kYawAt = 1800000,
                                 kTrackAt = 2500000;
  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    if (start_ == 0) start_ = now_us;
    const std::uint64_t t = now_us - start_;
    rate_mode = t >= kRateFrom && t < kYawAt;
    pitch_rate = t < kRateTo ? 10 : 0;
    if (t >= kYawAt) yaw = 10, pitch = 10;
    if (!track_sent_ && t >= kTrackAt) {
      track_centre();
      track_sent_ = true;
    }
    return TopotekClient::tick(now_us, out);
  }

 private:
  std::uint64_t start_ = 0;
  bool track_sent_ = false;
};

// Reads the version ten times a second (SkyDroid VER, Topotek VSN), each
// frame's checksum spoiled when `bad_checksum` (its last digit changed), with
// source `source` when given (U over the network: ArduPilot before PR #33803).
class VersionClient : public DriverClient {
 public:
  explicit VersionClient(bool skydroid, bool bad_checksum = false, char source = 0)
      : sky_(skydroid), bad_(bad_checksum), source_(source) {}
  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    std::string fr =
        build(source_ ? source_ : client, top::Header::fixed, 'D', 'r', sky_ ? "VER" : "VSN", "00");
    if (bad_) fr.back() = fr.back() == '0' ? '1' : '0';
    out.push_back(std::move(fr));
    return now_us + 100000;
  }
  void on_frame(const top::Frame&, std::uint64_t) override { ++answers; }
  int answers = 0;

 private:
  bool sky_, bad_;
  char source_;
};

// One frame of a recording as `topdump read --json` gives it: its time (s),
// addresses, control, identifier and its fields' numeric values.
struct DumpFrame {
  double time = 0;
  char src = 0, dst = 0, control = 0;
  std::string ident;
  bool from_device = false;  // not sent from the endpoint the first frame came from
  std::map<std::string, double> values;
};

// The frames of a recording of one client's run, as topdump reads it with
// `args` (--model): the client's from the endpoint its first frame came
// from, the device's from the port it serves or a port of its own (a real
// Topotek camera's reply port); a copy of the device's last frame to
// another of the client's ports (topdump's copy_of) is that frame again,
// not listed twice.
inline std::vector<DumpFrame> dump_frames(const std::string& pcap, const std::string& args = {}) {
  std::vector<DumpFrame> v;
  std::string client;  // the endpoint the client's first frame came from
  for (const auto& [line, j] : topdump_read_json(pcap, args).lines) {
    if (j.is_discarded() || j.value("type", "") != "frame") continue;
    if (!j.value("copy_of", nlohmann::json()).is_null()) continue;
    if (client.empty()) client = j.value("from", "");
    DumpFrame f;
    f.from_device = j.value("from", "") != client;
    f.time = j.value("time", 0.0);
    f.ident = j.value("ident", "");
    const std::string s = j.value("src", ""), d = j.value("dst", ""), c = j.value("control", "");
    f.src = s.empty() ? 0 : s[0];
    f.dst = d.empty() ? 0 : d[0];
    f.control = c.empty() ? 0 : c[0];
    if (j.contains("fields") && j["fields"].is_object())
      for (const auto& [k, x] : j["fields"].items())
        if (x.is_object() && x.contains("value") && x["value"].is_number())
          f.values[k] = x["value"].get<double>();
    v.push_back(std::move(f));
  }
  return v;
}

}  // namespace faultclients
