// The ports of TOP traffic, each with where it is written (DESIGN.md
// "Ports"): the simulator serves them, topdump recognises them, and the
// dialect detection starts from them.
#include "top/dialect.hpp"

namespace top {

namespace {

constexpr ModelSet kC10 = model_bit(Model::c10), kC20 = model_bit(Model::c20);
constexpr ModelSet kUdpSkydroid = skydroid_models & ~kC20;

constexpr PortSpec kPorts[] = {
    {5000, false, Dialect::skydroid, kUdpSkydroid, kUdpSkydroid, false, "SkyDroid 2.1.1: UDP 5000"},
    {5000, true, Dialect::skydroid, kC10 | kC20, kC20, false,
     "SkyDroid 2.1.1: the C10 also on TCP 5000, the C20 on TCP 5000 only"},
    {9002, false, Dialect::skydroid, kC10, kC10, false,
     "SkyDroid 2.1.1: the C10 also answers on UDP 9002"},
    {12580, false, Dialect::skydroid, skydroid_models, model_bit(Model::c12), false,
     "field: some C12 clients send every frame to UDP 5000 and 12580 both"},
    {9003, false, Dialect::topotek, topotek_models, topotek_models, false,
     "Topotek V1.1.3: the device listens on UDP 9003"},
    {9004, false, Dialect::topotek, topotek_models, 0, true,
     "Topotek V1.1.3: the device answers to UDP 9004 on the client"},
};

}  // namespace

std::span<const PortSpec> known_ports() noexcept { return kPorts; }

const PortSpec* default_port(Model m) noexcept {
  if (m == Model::unknown) return nullptr;
  for (const PortSpec& p : kPorts)
    if (p.served & model_bit(m)) return &p;
  return nullptr;
}

std::uint16_t client_port(Model m) noexcept {
  if (m == Model::unknown) return 0;
  for (const PortSpec& p : kPorts)
    if (p.client && (p.models & model_bit(m))) return p.port;
  return 0;
}

Dialect dialect_from_port(std::uint16_t port) noexcept {
  for (const PortSpec& p : kPorts)
    if (p.port == port) return p.dialect;
  return Dialect::unknown;
}

bool is_top_port(std::uint16_t port) noexcept {
  return dialect_from_port(port) != Dialect::unknown;
}

PortRole port_role(std::uint16_t port) noexcept {
  PortRole r = PortRole::unknown;
  for (const PortSpec& p : kPorts) {
    if (p.port != port) continue;
    if (p.client) return PortRole::client;
    r = PortRole::device;
  }
  return r;
}

}  // namespace top
