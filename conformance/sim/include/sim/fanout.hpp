// Where a device's UDP datagrams go on the client's host, as the UDP traits
// of top/device.hpp (ephemeral_reply_port, fan_out, duplicate_to_client_port)
// make a device send them. Pure: topsim's server (sim/server.hpp) sends to
// these ports, and topconf's in-process transport delivers the copies that
// reach its own port, so that both are the same device.
#pragma once

#include <cstdint>
#include <vector>

namespace topsim {

// The UDP traits as a device applies them (Device::udp_traits: the
// profile's traits, then the options).
struct UdpTraits {
  bool ephemeral_reply_port = false;  // sends from a port of its own, not the one it serves
  bool fan_out = false;               // to the client port and to the last other port that asked
  bool duplicate = false;             // two copies to the client port

  bool operator==(const UdpTraits&) const = default;
};

// The destinations of one device's datagrams, by port of the client's host
// (the host of the latest request; a request from another host starts
// afresh).
//
// Without fan-out a reply goes to the client port of the port table
// (Topotek V1.1.3: 9004), or to the asking port when there is none. With
// fan-out it goes to the last port other than the client port that asked
// (the asking port, unless that is the client port) and to the client port;
// with duplicate the client port gets two copies, an asking client port's
// own copy being one of them. A push goes where a reply to the last request
// would go. The rule is read off the PixEagle bench sessions that
// top::TraitKind::fan_out names, deterministic where the unit was not
// quite: see conformance/README.md (topsim, UDP traits).
class Fanout {
 public:
  // `client_port`: 0 for none (a SkyDroid device answers the asking port).
  Fanout(UdpTraits traits, std::uint16_t client_port) noexcept
      : traits_(traits), client_(client_port) {}

  // A request arrived from `port` (of the host the last request came
  // from, unless `new_host`): the ports its replies go to, in order.
  std::vector<std::uint16_t> request(std::uint16_t port, bool new_host = false);
  // The ports a push goes to now; none before the first request.
  std::vector<std::uint16_t> push() const;

  const UdpTraits& traits() const noexcept { return traits_; }
  std::uint16_t client_port() const noexcept { return client_; }

 private:
  std::vector<std::uint16_t> to(std::uint16_t asker) const;
  UdpTraits traits_;
  std::uint16_t client_ = 0;
  std::uint16_t last_asker_ = 0;  // 0: nobody asked yet
  std::uint16_t last_other_ = 0;  // the last asking port that is not the client port
};

}  // namespace topsim
