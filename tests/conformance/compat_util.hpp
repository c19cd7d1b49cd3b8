// What the agreement tests of topconf run --driver share (compat_test.cpp,
// compat_skydroid_test.cpp, compat_table_test.cpp): topconf's verdict on a
// variant, in process or against a topsim process, and the check that it
// is what a driver-like client lived through on the same variant.
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "binaries.hpp"
#include "loopback.hpp"
#include "sim/device.hpp"

struct Verdict {
  int rc = -1;
  nlohmann::json compat;  // the JSON's compatibility object
  std::string json_path;  // the report, when kept
  std::string verdict() const { return compat.value("verdict", ""); }
  std::set<std::string> lost() const {
    std::set<std::string> s;
    for (const auto& f : compat.value("features_lost", nlohmann::json::array()))
      s.insert(f.get<std::string>());
    return s;
  }
};

// Runs topconf run --driver `driver` --model `model` with `args`; its exit
// status and the JSON's compatibility object. `keep`: the JSON report is
// left at json_path (compat_<stem>.json in the build tree).
inline Verdict topconf_driver(const std::string& driver, const std::string& model,
                              const std::string& args, const std::string& stem, bool keep = false) {
  const std::string json = std::string(TOPKIT_BINARY_DIR) + "/compat_" + stem + ".json";
  std::remove(json.c_str());
  Verdict v;
  v.rc = run_cmd(bin("topconf") + " run --driver " + driver + " --model " + model + " -q --json " +
                 json + " " + args);
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_discarded()) {
    v.compat = j.value("compatibility", nlohmann::json());
    EXPECT_EQ(j.value("exit_code", -1), v.rc) << stem;
  }
  if (keep)
    v.json_path = json;
  else
    std::remove(json.c_str());
  return v;
}

// The same against a topsim process started with `topsim_args` (its
// --model is `model`): on a new pseudo-terminal when `pty`, else on UDP at
// the model's port of a loopback host of the test's own.
inline Verdict topconf_driver_process(const std::string& driver, const std::string& model,
                                      std::vector<std::string> topsim_args, bool pty,
                                      const std::string& stem, bool keep = false) {
  const std::string port = model == "sip" ? "9003" : "5000";
  const std::string host = own_loopback();
  topsim_args.insert(topsim_args.begin(), {"--model", model});
  if (pty)
    topsim_args.push_back("--pty");
  else
    topsim_args.insert(topsim_args.end(), {"--udp", host + ":" + port});
  std::string line;
  const pid_t pid = start_topsim(topsim_args, line);
  EXPECT_GT(pid, 0);
  if (pid <= 0) return {};
  const std::string target = pty ? "serial:" + line : "udp://" + host + ":" + port;
  Verdict v = topconf_driver(driver, model, "--target " + target, stem, keep);
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
  return v;
}

// What a driver-like client lived through: served (healthy, and what a
// must need gives it), and the features it lost, named as the profile
// names them.
struct Experience {
  bool served = false;
  std::set<std::string> lost;
  std::string why;  // what it lived through, for a failure's text
};

// Healthy over a run from `start_us` for `ms`, on the times of the
// attitude frames the client took: the first within 1.5 s of the start,
// never 1 s without one after it, the last within 1 s of the end.
template <class Attitudes>
bool healthy_throughout(const Attitudes& att, std::uint64_t start_us, std::uint64_t ms) {
  if (att.empty() || att.front().t_us - start_us >= 1500000) return false;
  for (std::size_t i = 1; i < att.size(); ++i)
    if (att[i].t_us - att[i - 1].t_us > 1000000) return false;
  // The last frame may be read just after the end (the harness stamps a
  // frame when it reads it): then it is 0 us before the end, not 2^64.
  const std::uint64_t end = start_us + ms * 1000;
  return att.back().t_us >= end || end - att.back().t_us <= 1000000;
}

// The attitude times `healthy_throughout` judged, for a failure's text:
// how many, the first after the start, the longest gap, the last before
// the end (ms).
template <class Attitudes>
std::string attitude_times(const Attitudes& att, std::uint64_t start_us, std::uint64_t ms) {
  if (att.empty()) return "no attitude";
  std::uint64_t gap = 0;
  for (std::size_t i = 1; i < att.size(); ++i) gap = std::max(gap, att[i].t_us - att[i - 1].t_us);
  return std::to_string(att.size()) + " attitudes, first " +
         std::to_string((att.front().t_us - start_us) / 1000) + " ms, longest gap " +
         std::to_string(gap / 1000) + " ms, last " +
         std::to_string((start_us + ms * 1000 - std::min(att.back().t_us, start_us + ms * 1000)) /
                        1000) +
         " ms before the end";
}

inline void expect_agreement(const Verdict& v, const Experience& e, const std::string& variant) {
  SCOPED_TRACE(variant + ": topconf says " + v.compat.value("text", "(none)") +
               "; the client: " + e.why);
  const std::string lived = !e.served        ? "incompatible"
                            : e.lost.empty() ? "compatible"
                                             : "compatible without";
  EXPECT_EQ(v.verdict(), lived);
  EXPECT_EQ(v.rc, lived == "incompatible" ? 1 : 0);
  if (e.served) {
    EXPECT_EQ(v.lost(), e.lost);
  }
}

// A file name stem of a variant's text.
inline std::string variant_stem(std::string s) {
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return s;
}

// A setting of the device's own options, written once: as topsim's
// command line takes it (`args`) and as the harness's topsim takes it
// (`set`). The settings the variants below are made of.
struct DeviceSetting {
  std::vector<std::string> args;
  std::function<void(topsim::DeviceOptions&)> set;
};

namespace setting {
// Reply addresses in request order (--reply-order request-order).
inline DeviceSetting request_order_replies() {
  return {{"--reply-order", "request-order"},
          [](topsim::DeviceOptions& o) { o.reply_order = top::Order::request_order; }};
}
// Replies and pushes both in request order.
inline DeviceSetting request_order_replies_and_pushes() {
  return {{"--reply-order", "request-order", "--push-order", "request-order"},
          [](topsim::DeviceOptions& o) {
            o.reply_order = top::Order::request_order;
            o.push_order = top::Order::request_order;
          }};
}
inline DeviceSetting fw_version(const std::string& v) {
  return {{"--fw-version", v}, [v](topsim::DeviceOptions& o) { o.version = v; }};
}
inline DeviceSetting write_echo() {
  return {{"--write-echo", "on"}, [](topsim::DeviceOptions& o) { o.write_echo = true; }};
}
inline DeviceSetting fixed_header_replies() {
  return {{"--reply-header", "TP"},
          [](topsim::DeviceOptions& o) { o.reply_header = top::Header::fixed; }};
}
inline DeviceSetting document_profile() {
  return {{"--profile", "document"},
          [](topsim::DeviceOptions& o) { o.profile = top::Profile::document; }};
}
}  // namespace setting

// A variant of the device's own options, not a fault: topconf runs against
// a topsim process given the setting's arguments (options_verdict), the
// client against the harness's topsim with the same setting (options_of).
// `verdict`, when given, pins what both say, with the features lost where
// the driver is served (expect_pinned).
struct OptionsVariant {
  const char* name;  // the test's, e.g. RequestOrderRepliesLoseEverything
  const char* model;
  DeviceSetting setting;
  const char* verdict = "";
  std::set<std::string> lost = {};
};

inline void PrintTo(const OptionsVariant& v, std::ostream* os) { *os << v.name; }
inline std::string variant_name(const ::testing::TestParamInfo<OptionsVariant>& i) {
  return i.param.name;
}

inline topsim::DeviceOptions options_of(const OptionsVariant& v) {
  topsim::DeviceOptions o;
  v.setting.set(o);
  return o;
}

// topconf run --driver `driver` against a topsim process with the
// variant's arguments, on a pseudo-terminal when `pty`, else over UDP.
inline Verdict options_verdict(const std::string& driver, const OptionsVariant& v, bool pty) {
  return topconf_driver_process(driver, v.model, v.setting.args, pty,
                                variant_stem(driver + "_" + v.name));
}

inline void expect_pinned(const Verdict& v, const OptionsVariant& p) {
  if (!*p.verdict) return;
  EXPECT_EQ(v.verdict(), p.verdict);
  // the features lost count where the driver is served (as in expect_agreement)
  if (std::string(p.verdict) != "incompatible") {
    EXPECT_EQ(v.lost(), p.lost);
  }
}
