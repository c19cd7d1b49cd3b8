// topconf run --driver ardupilot-skydroid (issue 49): on topsim variants
// the verdict topconf gives agrees with what the SkyDroid driver-like
// client (driver_skydroid.hpp: AP_Mount_SkyDroid's sends, cadence and
// parsing, docs/sources/ardupilot.md section 2) lives through over real
// UDP, the driver's only link ("control is over UDP only", the driver's
// header comment). The client is served when it stays healthy on full GAC
// frames and its angle loop, steering with GSY and GSP alone, brings both
// axes to their targets; it loses the firmware version or the model name
// when no VER or MOD reply it parses names one (not a placeholder).
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "compat_util.hpp"
#include "driver_harness.hpp"
#include "driver_skydroid.hpp"
#include "sim/faults.hpp"

namespace {

constexpr std::uint64_t kRunMs = 4000;

Experience skydroid_experience(top::Model model, const std::string& faults,
                               topsim::DeviceOptions o = {}) {
  std::string err;
  const auto fc = topsim::parse_faults(faults, err);
  EXPECT_TRUE(fc) << err;
  SkyDroidDriver c;
  c.target_yaw = 20;  // both axes move: GSY and GSP are its only motion commands
  const DriverRun r = run_driver(c, model, topsim::TransportKind::udp, kRunMs, "", o,
                                 fc ? *fc : topsim::FaultConfig{}, UdpClient::connected);
  Experience e;
  e.served = healthy_throughout(c.attitude, r.start_us, kRunMs);
  if (e.served) {
    const auto& a = c.attitude.back();
    double ey = a.yaw - c.target_yaw;
    while (ey > 180) ey -= 360;
    while (ey < -180) ey += 360;
    e.served = std::fabs(ey) <= 5 && std::fabs(a.pitch - c.target_pitch) <= 5;
    e.why = "healthy, its loop ended at yaw " + std::to_string(a.yaw) + ", pitch " +
            std::to_string(a.pitch);
  } else {
    e.why = "not healthy, GAC frames: " + attitude_times(c.attitude, r.start_us, kRunMs);
  }
  if (c.version.find_first_of("123456789") == std::string::npos) e.lost.insert("firmware version");
  if (c.model.find_first_not_of('0') == std::string::npos) e.lost.insert("model name");
  return e;
}

struct FaultVariant {
  const char* model;
  const char* faults;
};

void PrintTo(const FaultVariant& v, std::ostream* os) { *os << v.model << " '" << v.faults << "'"; }

class SkyDroidVariant : public ::testing::TestWithParam<FaultVariant> {};

// topconf's in-process topsim and the client's, with the same fault.
TEST_P(SkyDroidVariant, TheVerdictIsWhatTheClientLivesThrough) {
  const std::string model = GetParam().model, faults = GetParam().faults;
  const Verdict v = topconf_driver("ardupilot-skydroid", model,
                                   faults.empty() ? "" : "--sim-fault '" + faults + "'",
                                   variant_stem("skydroid_" + model + "_" + faults));
  const auto m = top::model_from_string(model);
  ASSERT_TRUE(m);
  expect_agreement(v, skydroid_experience(*m, faults),
                   model + " " + (faults.empty() ? "default" : faults));
}

// The default of both models; the attitude stream missing, stalled, or
// never switched on (GAA ignored); the identity it asks unanswered or
// placeholders; the needs graded info (SDC, FAI) unanswered; a fault of a
// feature it does not use (tracking); a rate command it steers with taken
// and ignored, or turning the axis the other way (topconf's motion check:
// the GAC attitude after a GSY or GSP of +20 deg/s).
INSTANTIATE_TEST_SUITE_P(
    Faults, SkyDroidVariant,
    ::testing::Values(FaultVariant{"c12", ""}, FaultVariant{"c13", ""},
                      FaultVariant{"c13", "no-stream=GAC"},
                      FaultVariant{"c12", "stall=GAC@0.5+1.5"}, FaultVariant{"c13", "ignore=GAA"},
                      FaultVariant{"c13", "ignore=VER"}, FaultVariant{"c12", "ignore=MOD"},
                      FaultVariant{"c13", "placeholder-identity"},
                      FaultVariant{"c12", "ignore=SDC+FAI"}, FaultVariant{"c13", "refuse-tracking"},
                      FaultVariant{"c13", "ignore-motion=GSP"}, FaultVariant{"c13", "invert=pitch"},
                      FaultVariant{"c12", "ignore-motion=GSY"}, FaultVariant{"c12", "invert=yaw"}));

class SkyDroidVariantOptions : public ::testing::TestWithParam<OptionsVariant> {};

// Variants of the device's own options, not faults: topconf against a
// topsim process over UDP, the client against the harness's topsim with
// the same options.
TEST_P(SkyDroidVariantOptions, TheVerdictIsWhatTheClientLivesThrough) {
  const OptionsVariant& p = GetParam();
  const auto m = top::model_from_string(p.model);
  ASSERT_TRUE(m);
  const Verdict v = options_verdict("ardupilot-skydroid", p, false);
  expect_agreement(v, skydroid_experience(*m, "", options_of(p)), p.name);
  expect_pinned(v, p);
}

// Replies and pushes that keep the asker's addresses are served; a version
// without the V the driver's parser needs first is lost; a short version,
// one number after the V, is taken.
INSTANTIATE_TEST_SUITE_P(
    Options, SkyDroidVariantOptions,
    ::testing::Values(OptionsVariant{"RequestOrderRepliesAndPushesAreServed", "c13",
                                     setting::request_order_replies_and_pushes(), "compatible"},
                      OptionsVariant{"AVersionWithoutItsVIsLost",
                                     "c12",
                                     setting::fw_version("1.0.78"),
                                     "compatible without",
                                     {"firmware version"}},
                      OptionsVariant{"AShortVersionIsTaken", "c13", setting::fw_version("V2"),
                                     "compatible"}),
    variant_name);

}  // namespace
