// The ports topsim serves a model on, read from the port table
// (top::known_ports(): SkyDroid 2.1.1, Topotek V1.1.3).
#include "sim/server.hpp"
#include "top/dialect.hpp"

namespace topsim {

std::uint16_t default_port(top::Model m) noexcept {
  const top::PortSpec* p = top::default_port(m);
  return p ? p->port : 0;
}

TransportKind default_transport(top::Model m) noexcept {
  const top::PortSpec* p = top::default_port(m);
  return p && p->tcp ? TransportKind::tcp : TransportKind::udp;
}

std::vector<std::uint16_t> extra_udp_ports(top::Model m) {
  std::vector<std::uint16_t> v;
  const top::PortSpec* first = top::default_port(m);
  for (const top::PortSpec& p : top::known_ports())
    if (&p != first && !p.tcp && m != top::Model::unknown && (p.served & top::model_bit(m)))
      v.push_back(p.port);
  return v;
}

}  // namespace topsim
