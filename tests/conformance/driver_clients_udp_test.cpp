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

// PixEagle (gimbal_interface.py @ 0724458) listens on 9004 whatever the
// source port: it hears every answer, twice, and reads the tracking state.
// Its angle parser looks for GAC or GIC in a packet; the real camera answers
// the GIC query with a 12-char GIA (top/device.hpp GIC -> GIA reply form),
// which it does not read: it gets no angles from its queries.
TEST(ClientSockets, PixEagleHearsTheRealUnitOn9004) {
  PixEagleClient c;
  const DriverRun r = run_driver(c, top::Model::sip, topsim::TransportKind::udp, 1500, {}, {}, {},
                                 UdpClient::pixeagle);
  ASSERT_GE(c.trc_sent, 2) << "sent " << r.sent;
  EXPECT_GE(c.trc, c.trc_sent);  // two copies of each answer, the last may be in flight
  EXPECT_GE(c.gia, c.gic_sent);
  ASSERT_FALSE(c.states.empty());
  for (int s : c.states) EXPECT_EQ(s, 0);  // not tracking
  EXPECT_TRUE(c.angles.empty());           // GIA named neither GAC nor GIC
  // The document's device answers GIC with GIC (Topotek 4.3.5), once, from
  // 9003 to 9004: its angles are read.
  PixEagleClient d;
  topsim::DeviceOptions doc;
  doc.profile = top::Profile::document;
  run_driver(d, top::Model::sip, topsim::TransportKind::udp, 1500, {}, doc, {},
             UdpClient::pixeagle);
  EXPECT_FALSE(d.angles.empty());
  EXPECT_EQ(d.gia, 0);
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
