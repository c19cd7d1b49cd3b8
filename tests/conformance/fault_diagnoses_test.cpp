// topsim's faults for the field diagnoses (issue 29 item 5): a well-behaved
// client (fault_clients.hpp) over real UDP against topsim with one fault;
// `topdump read --json` on topsim's recording names the diagnosis the fault
// shows, and the same client against the healthy device names none. The
// motion faults are checked on the recording itself too: the commands
// echoed, the attitude unchanged or moving the other way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "fault_clients.hpp"
#include "sim/faults.hpp"
#include "top/diagnoses.hpp"

namespace {

using faultclients::DumpFrame;

enum class Client { sky, topotek, version, bad_checksum, uart_source };

std::unique_ptr<DriverClient> make_client(Client c, top::Model m) {
  const bool sky = top::dialect_of(m) == top::Dialect::skydroid;
  switch (c) {
    case Client::sky:
      return std::make_unique<faultclients::SkyClient>(m != top::Model::c13);
    case Client::topotek:
      return std::make_unique<faultclients::TopoClient>();
    case Client::version:
      return std::make_unique<faultclients::VersionClient>(sky);
    case Client::bad_checksum:
      return std::make_unique<faultclients::VersionClient>(sky, true);
    case Client::uart_source:
      return std::make_unique<faultclients::VersionClient>(sky, false, 'U');
  }
  return nullptr;
}

Client client_of(top::Model m) {
  return top::dialect_of(m) == top::Dialect::skydroid ? Client::sky : Client::topotek;
}

topsim::FaultConfig faults(const std::string& spec) {
  std::string err;
  auto f = topsim::parse_faults(spec, err);
  EXPECT_TRUE(f.has_value()) << spec << ": " << err;
  return f.value_or(topsim::FaultConfig{});
}

struct Recorded {
  std::string pcap;
  Dump dump;
  ~Recorded() { std::remove(pcap.c_str()); }
};

// Runs `client` against `model` with `spec` over UDP for `ms`, and reads the
// recording back.
std::unique_ptr<Recorded> record(const std::string& name, top::Model model, Client client,
                                 const std::string& spec, std::uint64_t ms = 3500,
                                 top::Profile profile = top::Profile::field) {
  auto r = std::make_unique<Recorded>();
  r->pcap = std::string(TOPKIT_BINARY_DIR) + "/fault_" + name + ".pcap";
  auto c = make_client(client, model);
  topsim::DeviceOptions options;
  options.profile = profile;
  run_driver(*c, model, topsim::TransportKind::udp, ms, r->pcap, options, faults(spec));
  r->dump = topdump_findings(r->pcap, "warning", topdump_args(model, topsim::TransportKind::udp));
  return r;
}

// The diagnosis codes among a dump's findings.
std::vector<std::string> diagnoses(const Dump& d) {
  std::vector<std::string> v;
  for (const DumpFinding& f : d.findings)
    if (top::diagnosis_from_string(f.code) && std::find(v.begin(), v.end(), f.code) == v.end())
      v.push_back(f.code);
  return v;
}

std::string model_name(top::Model m) { return std::string(top::to_string(m)); }

// ---- the healthy device: no diagnosis, no warning ------------------------

class Healthy : public ::testing::TestWithParam<top::Model> {};

TEST_P(Healthy, TheWellBehavedClientsRecordingNamesNothing) {
  const top::Model m = GetParam();
  for (const Client c : {client_of(m), Client::version}) {
    const auto r =
        record("healthy_" + model_name(m) + (c == Client::version ? "_version" : ""), m, c, "");
    EXPECT_EQ(r->dump.status, 0) << describe(r->dump);
    EXPECT_TRUE(r->dump.findings.empty()) << describe(r->dump);
  }
}

// The document profile (topsim --profile document): the same clients' runs
// raise no warning or error diagnosis either (the motion diagnoses judge a
// command by the convention of the attitude it is compared with).
TEST_P(Healthy, TheDocumentProfileNamesNoDiagnosis) {
  const top::Model m = GetParam();
  const auto r =
      record("healthy_doc_" + model_name(m), m, client_of(m), "", 3500, top::Profile::document);
  for (const DumpFinding& f : r->dump.findings)
    EXPECT_FALSE(top::diagnosis_from_string(f.code)) << describe(r->dump);
}

INSTANTIATE_TEST_SUITE_P(Models, Healthy,
                         ::testing::Values(top::Model::c12, top::Model::c13, top::Model::sip),
                         [](const auto& i) { return model_name(i.param); });

// ---- one fault, one diagnosis ---------------------------------------------

struct Case {
  const char* name;
  top::Model model;
  Client client;
  const char* faults;
  const char* code;  // the diagnosis topdump must name
};

std::ostream& operator<<(std::ostream& o, const Case& c) { return o << c.name; }

class FaultNamesItsDiagnosis : public ::testing::TestWithParam<Case> {};

TEST_P(FaultNamesItsDiagnosis, OverUdp) {
  const Case& c = GetParam();
  ASSERT_TRUE(top::diagnosis_from_string(c.code)) << c.code;
  const auto r = record(c.name, c.model, c.client, c.faults);
  const std::vector<std::string> found = diagnoses(r->dump);
  EXPECT_NE(std::find(found.begin(), found.end(), c.code), found.end())
      << c.faults << " on " << model_name(c.model) << ": " << describe(r->dump);
  // A warning diagnosis: topdump's exit status says so.
  EXPECT_EQ(r->dump.status, 1) << describe(r->dump);
}

INSTANTIATE_TEST_SUITE_P(
    Faults, FaultNamesItsDiagnosis,
    ::testing::Values(
        // the GAC push stops 1 s after GAA for 1.5 s, then resumes
        Case{"stall_c12", top::Model::c12, Client::sky, "stall=GAC@1+1.5", "stream-stalled"},
        Case{"stall_c13", top::Model::c13, Client::sky, "stall=GAC@1+1.5", "stream-stalled"},
        Case{"stall_sip", top::Model::sip, Client::topotek, "stall=GIA@1+1.5", "stream-stalled"},
        // GAA/GIA echoed, no push ever
        Case{"no_stream_c12", top::Model::c12, Client::sky, "no-stream=GAC",
             "stream-never-started"},
        Case{"no_stream_sip", top::Model::sip, Client::topotek, "no-stream=GIA",
             "stream-never-started"},
        // VER (SkyDroid), VSN and PA2 (Topotek) answer factory placeholders
        Case{"placeholder_c12", top::Model::c12, Client::sky, "placeholder-identity",
             "placeholder-identity"},
        Case{"placeholder_c13", top::Model::c13, Client::sky, "placeholder-identity",
             "placeholder-identity"},
        Case{"placeholder_sip", top::Model::sip, Client::topotek, "placeholder-identity",
             "placeholder-identity"},
        // the time set (TIM, UTC) answered one month early
        Case{"clock_c12", top::Model::c12, Client::sky, "clock=month-early", "clock-offset"},
        Case{"clock_sip", top::Model::sip, Client::topotek, "clock=month-early", "clock-offset"},
        // TRC answers state 4 (Topotek only: SkyDroid has no tracking)
        Case{"refuse_tracking_sip", top::Model::sip, Client::topotek, "refuse-tracking",
             "tracking-refused"},
        // every request ignored: the device says nothing
        Case{"ignore_c12", top::Model::c12, Client::version, "ignore=VER", "silent-device"},
        Case{"ignore_sip", top::Model::sip, Client::version, "ignore=VSN", "silent-device"},
        // requests with a bad checksum: the device drops them (no fault needed)
        Case{"bad_checksum_c12", top::Model::c12, Client::bad_checksum, "", "dropped-bad-checksum"},
        Case{"bad_checksum_sip", top::Model::sip, Client::bad_checksum, "", "dropped-bad-checksum"},
        // Topotek requests with source U over UDP: the device answers its UART
        // only (no fault needed)
        Case{"uart_source_sip", top::Model::sip, Client::uart_source, "", "reply-interface"},
        // the attitude stops at 1 s for good while the client's angle
        // targets (from 1.8 s, ten a second) keep coming
        Case{"stale_sip", top::Model::sip, Client::topotek, "stall=GIA@1+2.5", "attitude-stale"}),
    [](const auto& i) { return std::string(i.param.name); });

// ---- the motion faults, on the recording ----------------------------------

// The device's attitude (GAC pushes; Topotek 12-char GIA) in the recording:
// (time since the first frame, yaw, pitch) as topdump decodes them.
struct Attitude {
  double t, yaw, pitch;
};
std::vector<Attitude> attitude(const std::vector<DumpFrame>& frames) {
  std::vector<Attitude> v;
  const double t0 = frames.empty() ? 0 : frames.front().time;
  for (const DumpFrame& f : frames)
    if ((f.ident == "GAC" || f.ident == "GIA") && f.from_device && f.values.count("yaw") &&
        f.values.count("pitch"))
      v.push_back({f.time - t0, f.values.at("yaw"), f.values.at("pitch")});
  return v;
}

// The attitude nearest `t` s.
Attitude at(const std::vector<Attitude>& a, double t) {
  return *std::min_element(a.begin(), a.end(), [t](const Attitude& x, const Attitude& y) {
    return std::fabs(x.t - t) < std::fabs(y.t - t);
  });
}

// The writes of `ident` the device sent (`from_device`) or the client did.
std::size_t writes(const std::vector<DumpFrame>& frames, std::string_view ident, bool from_device) {
  return static_cast<std::size_t>(std::count_if(frames.begin(), frames.end(), [&](const auto& f) {
    return f.ident == ident && f.from_device == from_device && f.control == 'w';
  }));
}

class MotionFault : public ::testing::TestWithParam<top::Model> {};

// invert=pitch:rate: the pitch rate (GSP, YPR) moves pitch opposite to the
// healthy device's; the angle targets still move as they did.
TEST_P(MotionFault, InvertedPitchRateMovesTheOtherWay) {
  const top::Model m = GetParam();
  const auto healthy = record("motion_" + model_name(m), m, client_of(m), "");
  const auto fault = record("invert_" + model_name(m), m, client_of(m), "invert=pitch:rate");
  const auto h = attitude(
      faultclients::dump_frames(healthy->pcap, topdump_args(m, topsim::TransportKind::udp)));
  const auto f =
      attitude(faultclients::dump_frames(fault->pcap, topdump_args(m, topsim::TransportKind::udp)));
  ASSERT_GE(h.size(), 20u);
  ASSERT_GE(f.size(), 20u);
  // pitch over the rate phase (0.5 s to 1.5 s after the start)
  const double dh = at(h, 1.6).pitch - at(h, 0.4).pitch;
  const double df = at(f, 1.6).pitch - at(f, 0.4).pitch;
  EXPECT_GT(std::fabs(dh), 5.0) << "healthy pitch moved " << dh;
  EXPECT_GT(std::fabs(df), 5.0) << "inverted pitch moved " << df;
  EXPECT_LT(dh * df, 0) << "healthy " << dh << ", inverted " << df;
  // topdump names it on the fault's recording, not on the healthy one's
  auto names = [](const Recorded& r, const char* code) {
    const auto v = diagnoses(r.dump);
    return std::find(v.begin(), v.end(), code) != v.end();
  };
  EXPECT_TRUE(names(*fault, "direction-inverted")) << describe(fault->dump);
  EXPECT_FALSE(names(*healthy, "direction-inverted")) << describe(healthy->dump);
  // the yaw angle target is reached the same way in both
  EXPECT_NEAR(h.back().yaw, f.back().yaw, 1.0);
}

// ignore-motion=GAY: GAY is echoed, yaw stays where it was; the pitch rate
// still moves pitch.
TEST_P(MotionFault, IgnoredAngleCommandIsEchoedAndNothingMoves) {
  const top::Model m = GetParam();
  const auto healthy = record("motion2_" + model_name(m), m, client_of(m), "");
  const auto fault = record("ignore_motion_" + model_name(m), m, client_of(m), "ignore-motion=GAY");
  const auto hf =
      faultclients::dump_frames(healthy->pcap, topdump_args(m, topsim::TransportKind::udp));
  const auto ff =
      faultclients::dump_frames(fault->pcap, topdump_args(m, topsim::TransportKind::udp));
  const auto h = attitude(hf);
  const auto f = attitude(ff);
  ASSERT_GE(h.size(), 20u);
  ASSERT_GE(f.size(), 20u);
  // every GAY echoed (the last one may be in flight at the end of the run)
  const std::size_t sent = writes(ff, "GAY", false), echoed = writes(ff, "GAY", true);
  EXPECT_GE(sent, 1u);
  EXPECT_GE(echoed + 1, sent);
  EXPECT_LE(echoed, sent);
  EXPECT_GT(std::fabs(h.back().yaw), 5.0) << "the healthy device turned yaw";
  for (const Attitude& a : f) EXPECT_NEAR(a.yaw, 0, 0.05) << "at " << a.t << " s";
  EXPECT_GT(std::fabs(at(f, 1.6).pitch - at(f, 0.4).pitch), 5.0) << "pitch still moves";
  // topdump names it on the fault's recording, not on the healthy one's
  auto names = [](const Recorded& r, const char* code) {
    const auto v = diagnoses(r.dump);
    return std::find(v.begin(), v.end(), code) != v.end();
  };
  EXPECT_TRUE(names(*fault, "command-ignored")) << describe(fault->dump);
  EXPECT_FALSE(names(*healthy, "command-ignored")) << describe(healthy->dump);
}

INSTANTIATE_TEST_SUITE_P(Models, MotionFault, ::testing::Values(top::Model::c12, top::Model::sip),
                         [](const auto& i) { return model_name(i.param); });

}  // namespace
