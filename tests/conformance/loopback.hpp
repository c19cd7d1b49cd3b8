// A loopback address of the test's own (127.A.B.C), a host of its own on
// this machine: a device served there on its fixed ports (Topotek 9003,
// SkyDroid 5000), and the copies a real Topotek camera sends to UDP 9004 of
// its client's host, reach this test's sockets and no other's. Tests of
// other builds beside it, and the tests of this one, run at the same time
// on one machine; every 127.x.y.z is loopback on Linux.
#pragma once

#include <unistd.h>

#include <atomic>
#include <string>

// A new address on each call: 127.(100 + n % 100).(pid / 254 % 256).(1 + pid % 254).
inline std::string own_loopback() {
  static std::atomic<unsigned> n{0};
  const auto pid = static_cast<unsigned>(::getpid());
  return "127." + std::to_string(100 + n++ % 100) + "." + std::to_string(pid / 254 % 256) + "." +
         std::to_string(1 + pid % 254);
}
