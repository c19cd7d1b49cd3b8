// topsim's faults for topconf drive (docs/DRIVE.md): stop=, ere=,
// range-form=, late=, checksum-case=, reboot=, each parsed and what it does
// to the device or the line; Device::reconfigure (--persistent) keeps the
// state; Server::visit and reboot= on a running server.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "sim/device.hpp"
#include "sim/faults.hpp"
#include "sim/server.hpp"
#include "sim_test_util.hpp"

namespace {

using topsim::Device;
using topsim::Link;

std::size_t pushes_between(Device& d, std::uint64_t from, std::uint64_t to) {
  std::size_t n = 0;
  for (std::uint64_t t = from; t <= to; t += 10000) {
    std::vector<std::string> out;
    d.poll(t, out);
    n += out.size();
  }
  return n;
}

TEST(DriveFaults, ParseAndReject) {
  const topsim::FaultConfig f = faults_of(
      "stop=GAC@0.5,ere=CAP,range-form=short,late=VSN@1500,checksum-case=0.5,reboot=1.25");
  ASSERT_EQ(f.device.stops.size(), 1u);
  EXPECT_EQ(f.device.stops[0].ident, "GAC");
  EXPECT_EQ(f.device.stops[0].from_us, 500000u);
  EXPECT_EQ(f.device.ere, std::vector<std::string>{"CAP"});
  EXPECT_TRUE(f.device.range_short);
  ASSERT_EQ(f.late.size(), 1u);
  EXPECT_EQ(f.late[0].ident, "VSN");
  EXPECT_EQ(f.late[0].ms, 1500u);
  EXPECT_DOUBLE_EQ(f.checksum_case, 0.5);
  EXPECT_EQ(f.reboot_us, 1250000u);
  EXPECT_TRUE(f.any());
  for (const char* bad :
       {"stop=XYZ@1", "stop=GAC", "ere=CA", "range-form=long", "late=VSN", "late=VSNX@1",
        "late=VSN@-1", "checksum-case=2", "reboot=0", "reboot=x"}) {
    std::string err;
    EXPECT_FALSE(topsim::parse_faults(bad, err).has_value()) << bad;
    EXPECT_NE(err.find(std::string(bad).substr(0, 4)), std::string::npos) << bad << ": " << err;
  }
}

// stop=: the stream stops once, 0.5 s after it started; switched on again
// it keeps going.
TEST(DriveFaults, StopSwitchesTheStreamOffOnce) {
  topsim::DeviceOptions o;
  o.faults = faults_of("stop=GAC@0.5").device;
  Device d(top::Model::c12, o);
  ask(d, "#TPUG2wGAA0A", 0);  // 10 Hz
  EXPECT_GE(pushes_between(d, 0, 450000), 4u);
  EXPECT_EQ(pushes_between(d, 600000, 2000000), 0u) << "the stream must stop";
  ask(d, "#TPUG2wGAA0A", 2000000);
  EXPECT_GE(pushes_between(d, 2000000, 4000000), 15u) << "switched on again, it runs";
}

TEST(DriveFaults, EreAnswersTheCommandWithEre) {
  topsim::DeviceOptions o;
  o.faults = faults_of("ere=CAP").device;
  Device d(top::Model::c12, o);
  const auto out = ask(d, "#TPUD2wCAP01", 0);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].ident_view(), "ERE");
  Device healthy(top::Model::c12);
  const auto ok = ask(healthy, "#TPUD2wCAP01", 0);
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_EQ(ok[0].ident_view(), "CAP");
  // Topotek has no ERE: silence.
  topsim::DeviceOptions t;
  t.faults = faults_of("ere=CAP").device;
  Device sip(top::Model::sip, t);
  EXPECT_TRUE(ask(sip, "#TPPD2wCAP01", 0).empty());
}

TEST(DriveFaults, RangeFormShortDropsThePadding) {
  for (const bool short_form : {false, true}) {
    topsim::DeviceOptions o;
    o.range_m = 12.5;
    o.faults.range_short = short_form;
    Device d(top::Model::sip, o);
    const auto out = ask(d, "#TPPD2wLRF02", 0);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].data(), short_form ? "12.5" : "00012.5");
  }
}

TEST(DriveFaults, LateAndChecksumCaseOnTheLine) {
  topsim::FaultInjector late(faults_of("late=VSN@1500"), 1);
  std::vector<topsim::Emission> em;
  late.apply(top::with_checksum("#tpDPArVSN1.6.26.R.D"), false, em);
  late.apply(top::with_checksum("#TPGP2wGIA01"), false, em);
  ASSERT_EQ(em.size(), 2u);
  EXPECT_EQ(em[0].delay_us, 1500000u);
  EXPECT_EQ(em[1].delay_us, 0u);
  topsim::FaultInjector lower(faults_of("checksum-case=1"), 1);
  em.clear();
  // #TPUG2wGAA32 sums to 0x3A: the letter goes lowercase.
  lower.apply("#TPUG2wGAA323A", false, em);
  ASSERT_EQ(em.size(), 1u);
  EXPECT_EQ(em[0].bytes, "#TPUG2wGAA323a");
}

TEST(DriveFaults, ReconfigureKeepsAxesAndStreams) {
  Device d(top::Model::c12);
  ask(d, "#TPUG2wGAA0A", 0);
  ask(d, "#TPUG2wGSP14", 0);  // +10 deg/s up
  std::vector<std::string> out;
  d.poll(500000, out);
  const double pitch = d.pitch().angle;
  EXPECT_GT(pitch, 3);
  topsim::DeviceOptions o;
  o.faults = faults_of("stop=GAC@0.3").device;
  d.reconfigure(o, 500000);
  EXPECT_DOUBLE_EQ(d.pitch().angle, pitch);
  EXPECT_GE(pushes_between(d, 500000, 750000), 2u) << "the stream survives the change";
  EXPECT_EQ(pushes_between(d, 850000, 1500000), 0u) << "the new case's stop counts from it";
}

// reboot= on a running server: the stream a client switched on is off after
// the power cycle (Server::visit sees the device on the server's thread);
// reconfigure() keeps it on.
int streams_on(topsim::Server& s) {
  int n = -1;
  EXPECT_TRUE(s.visit([&](const Device& d, std::uint64_t) {
    n = 0;
    for (const topsim::Stream& x : d.streams()) n += x.period_us != 0;
  }));
  return n;
}

TEST(DriveFaults, RebootOnARunningServerSwitchesStreamsOff) {
  topsim::ServerConfig cfg;
  cfg.model = top::Model::c12;
  cfg.kind = topsim::TransportKind::udp;
  cfg.faults = faults_of("reboot=0.4");
  topsim::Server s(cfg);
  std::thread t([&] { s.run(); });
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(s.port());
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const std::string gaa = top::with_checksum("#TPUG2wGAA0A");
  ASSERT_EQ(::sendto(fd, gaa.data(), gaa.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to),
            static_cast<ssize_t>(gaa.size()));
  bool on = false;
  for (int i = 0; i < 20 && !on; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    on = streams_on(s) == 1;
  }
  EXPECT_TRUE(on) << "GAA switched the stream on";
  EXPECT_LT(s.now_us(), 400000u);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(streams_on(s), 0) << "the reboot at 0.4 s switched it off";
  // A change of case in place keeps a stream on.
  ASSERT_EQ(::sendto(fd, gaa.data(), gaa.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to),
            static_cast<ssize_t>(gaa.size()));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(s.reconfigure(faults_of("stop=GAC@5"), topsim::DeviceOptions{}));
  EXPECT_EQ(streams_on(s), 1);
  ::close(fd);
  s.stop();
  t.join();
}

}  // namespace
