// topconf run --driver pixeagle (issue 49): on topsim variants the verdict
// topconf gives agrees with what the PixEagle driver-like client
// (pixeagle_client.hpp: GimbalInterface @ 3bea324, the version the profile
// reads) lives through over real UDP, its only link: queries from an
// unbound socket to UDP 9003, answers read on UDP 9004. The client is
// served when the gimbal-body angles it takes from validated GAC answers
// stay fresh (healthy_throughout); it loses the tracking state when no
// validated TRC answer gives one.
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "compat_util.hpp"
#include "driver_harness.hpp"
#include "pixeagle_client.hpp"
#include "sim/faults.hpp"

namespace {

constexpr std::uint64_t kPixEagleRunMs = 3000;

Experience pixeagle_experience(const std::string& faults, topsim::DeviceOptions o = {}) {
  std::string err;
  const auto fc = topsim::parse_faults(faults, err);
  EXPECT_TRUE(fc) << err;
  PixEagleClient c;
  const DriverRun r = run_driver(c, top::Model::sip, topsim::TransportKind::udp, kPixEagleRunMs, "",
                                 o, fc ? *fc : topsim::FaultConfig{}, UdpClient::pixeagle);
  Experience e;
  e.served = healthy_throughout(c.angles, r.start_us, kPixEagleRunMs);
  if (c.states.empty()) e.lost.insert("tracking state");
  e.why = std::to_string(c.angles.size()) + " GAC angles of " + std::to_string(c.gac_sent) +
          " queries, " + std::to_string(c.states.size()) + " TRC states, " +
          std::to_string(c.spatial) + " spatial diagnostics, " + std::to_string(c.packets) +
          " frames heard";
  return e;
}

class PixEagleVariant : public ::testing::TestWithParam<const char*> {};

// topconf's in-process topsim and the client's, with the same fault.
TEST_P(PixEagleVariant, TheVerdictIsWhatTheClientLivesThrough) {
  const std::string faults = GetParam();
  const Verdict v =
      topconf_driver("pixeagle", "sip", faults.empty() ? "" : "--sim-fault '" + faults + "'",
                     variant_stem("pixeagle_" + faults));
  expect_agreement(v, pixeagle_experience(faults), faults.empty() ? "default" : faults);
  if (faults.empty()) {
    EXPECT_EQ(v.verdict(), "compatible");
  }
}

// The default; a command it sends unanswered (GAC: its angles; TRC: its
// tracking state; GIC: a diagnostic only); the identity placeholders and a
// lens that cannot track (state 4, a state it reads); pushes it never asks
// for, missing or stalled; replies that keep the asker's addresses, a
// checksum the header case no longer matches, a bad checksum.
INSTANTIATE_TEST_SUITE_P(Faults, PixEagleVariant,
                         ::testing::Values("", "ignore=GAC", "ignore=TRC", "ignore=GIC",
                                           "placeholder-identity", "refuse-tracking",
                                           "no-stream=GIA", "stall=GIA@0.5+1.5", "no-swap",
                                           "header-case=1", "bad-checksum=1"));

class PixEagleVariantOptions : public ::testing::TestWithParam<OptionsVariant> {};

// topconf against a topsim process with the variant's arguments, the
// client against the harness's topsim with the same options.
TEST_P(PixEagleVariantOptions, TheVerdictIsWhatTheClientLivesThrough) {
  const OptionsVariant& p = GetParam();
  expect_agreement(options_verdict("pixeagle", p, false), pixeagle_experience("", options_of(p)),
                   p.name);
}

// Replies that keep the asker's addresses; writes echoed; fixed-form (#TP)
// answers (PixEagle takes GAC only as #tpGPC); the document profile (#TP
// answers from the served port, no fan-out).
INSTANTIATE_TEST_SUITE_P(
    Options, PixEagleVariantOptions,
    ::testing::Values(OptionsVariant{"RequestOrderRepliesLoseEverything", "sip",
                                     setting::request_order_replies()},
                      OptionsVariant{"WriteEchoChangesNothing", "sip", setting::write_echo()},
                      OptionsVariant{"FixedHeaderRepliesLoseTheAngles", "sip",
                                     setting::fixed_header_replies()},
                      OptionsVariant{"TheDocumentProfile", "sip", setting::document_profile()}),
    variant_name);

}  // namespace
