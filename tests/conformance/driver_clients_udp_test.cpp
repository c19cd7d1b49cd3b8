// The public clients' UDP sockets against topsim's default sip, which
// answers as a real Topotek camera does: from a port of its own, to the
// asking port and twice to UDP 9004 of the asker's host (top::traits():
// ephemeral_reply_port, fan_out, duplicate_to_client_port). Each client
// binds and connects as its source does (driver_harness.hpp UdpClient).
#include <gtest/gtest.h>

#include "driver_harness.hpp"
#include "fault_clients.hpp"
#include "pixeagle_client.hpp"

namespace {

// PixEagle (gimbal_interface.py @ 3bea324) listens on 9004 whatever the
// source port: it hears every answer, twice, and reads the tracking state.
// It takes angles only from a GAC answer in the #tpGPC form, which the real
// camera's form gives (#tpGPCrGAC + 12 hex); the GIC query's answer, a
// 12-char GIA (top/device.hpp GIC -> GIA reply form), it keeps as a
// spatial diagnostic only.
TEST(ClientSockets, PixEagleHearsTheRealUnitOn9004) {
  PixEagleClient c;
  const DriverRun r = run_driver(c, top::Model::sip, topsim::TransportKind::udp, 1500, {}, {}, {},
                                 UdpClient::pixeagle);
  ASSERT_GE(c.trc_sent, 2) << "sent " << r.sent;
  EXPECT_GE(c.trc, c.trc_sent);  // two copies of each answer, the last may be in flight
  EXPECT_GE(c.gia, c.gic_sent);
  EXPECT_GE(c.spatial, c.gic_sent);
  ASSERT_FALSE(c.states.empty());
  for (int s : c.states) EXPECT_EQ(s, 0);  // not tracking
  EXPECT_GE(c.angles.size(), 2 * static_cast<std::size_t>(c.gac_sent) - 2);
  // Answers that keep the asker's addresses first (#tpPGC...) fail its
  // framing check: neither angles nor a state.
  PixEagleClient d;
  topsim::DeviceOptions request_order;
  request_order.reply_order = top::Order::request_order;
  run_driver(d, top::Model::sip, topsim::TransportKind::udp, 1500, {}, request_order, {},
             UdpClient::pixeagle);
  EXPECT_GT(d.packets, 0);
  EXPECT_TRUE(d.angles.empty());
  EXPECT_TRUE(d.states.empty());
  EXPECT_EQ(d.spatial, 0);
}

// ArduPilot master's NET_Pn UDP client connect()s its socket to the camera's
// address and port (AP_Networking_port.cpp @ d0678504, udp_client_loop): the
// kernel drops the camera's answers from its own port, and the driver hears
// nothing; PR #34227 (open) stops connecting for that reason, as the
// unconnected client of the driver tests does. A device answering from the
// port it serves is heard by either.
TEST(ClientSockets, ArduPilotsConnectedSocketHearsNothingFromTheRealUnit) {
  for (const UdpClient how : {UdpClient::connected, UdpClient::unconnected}) {
    for (const bool served : {false, true}) {
      faultclients::VersionClient c(false);
      topsim::DeviceOptions o;
      if (served) o.ephemeral_reply_port = false;
      const DriverRun r =
          run_driver(c, top::Model::sip, topsim::TransportKind::udp, 1000, {}, o, {}, how);
      const bool hears = how == UdpClient::unconnected || served;
      if (hears) {
        EXPECT_GE(c.answers, 5) << "sent " << r.sent << (served ? ", served" : "");
      } else {
        EXPECT_EQ(c.answers, 0) << "sent " << r.sent;
      }
    }
  }
}

}  // namespace
