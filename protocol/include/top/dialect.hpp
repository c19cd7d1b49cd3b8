// Dialect detection from ports, addresses, headers and identifiers.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "top/catalog.hpp"
#include "top/frame.hpp"

namespace top {

// A port the documents or field reports use for TOP traffic.
struct PortSpec {
  std::uint16_t port = 0;
  bool tcp = false;  // false: UDP
  Dialect dialect = Dialect::unknown;
  ModelSet models = 0;      // the models that use it
  ModelSet served = 0;      // the models whose device serves it unless told otherwise
  bool client = false;      // the client's end (where a Topotek device answers)
  std::string_view source;  // where it is written: a document section or field reports
};

// Every known port with its transport (src/ports.cpp): SkyDroid UDP 5000
// (C10 also TCP 5000 and UDP 9002; C20 TCP 5000; field: UDP 12580), Topotek
// UDP 9003 (device) and 9004 (client).
std::span<const PortSpec> known_ports() noexcept;

// The first port a device of the model serves by default: UDP 5000 (TCP for
// the C20), UDP 9003 for the SIP; null for unknown.
const PortSpec* default_port(Model m) noexcept;

// The port on the client a device of the model sends replies to (Topotek
// 9004); 0 when it answers the request's source port.
std::uint16_t client_port(Model m) noexcept;

// The dialect a known port implies (either transport): 5000, 9002, 12580
// -> skydroid; 9003, 9004 -> topotek; others unknown.
Dialect dialect_from_port(std::uint16_t port) noexcept;

// True for the ports the documents and field reports use for TOP traffic.
bool is_top_port(std::uint16_t port) noexcept;

// Which end of a conversation a well-known port belongs to: the device
// (SkyDroid 5000, 9002, 12580; Topotek 9003) or the client (Topotek 9004,
// the port the Topotek document sends replies to).
enum class PortRole : std::uint8_t { unknown, device, client };
PortRole port_role(std::uint16_t port) noexcept;

// The dialect one frame points to, unknown when it says nothing: a P
// address, an extended header or an identifier only Topotek defines point
// to topotek; an identifier only SkyDroid defines points to skydroid.
Dialect dialect_from_frame(const Frame& f) noexcept;

// Accumulates evidence for one conversation. An override wins; otherwise
// the frames' evidence, then the port's, decide.
class DialectDetector {
 public:
  void force(Dialect d) noexcept { forced_ = d; }
  void observe_port(std::uint16_t port) noexcept;
  void observe(const Frame& f) noexcept;
  // Asked for every frame, so inline.
  Dialect current() const noexcept {
    if (forced_ != Dialect::unknown) return forced_;
    if (votes_skydroid_ > votes_topotek_) return Dialect::skydroid;
    if (votes_topotek_ > votes_skydroid_) return Dialect::topotek;
    return port_;
  }

 private:
  Dialect forced_ = Dialect::unknown;
  Dialect port_ = Dialect::unknown;
  std::uint32_t votes_skydroid_ = 0;
  std::uint32_t votes_topotek_ = 0;
};

}  // namespace top
