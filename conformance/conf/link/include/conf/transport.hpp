// topconf's transports: how the runner reaches a device. The runner only
// sees this interface, so it runs the same against an in-process topsim
// (virtual clock), UDP, TCP or a serial line.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "pcapio/writer.hpp"
#include "sim/device.hpp"
#include "sim/faults.hpp"
#include "sim/intake.hpp"

namespace topconf {

// A transport failure (cannot connect, socket error, device gone).
struct TransportError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Transport {
 public:
  virtual ~Transport() = default;
  // Microseconds on the transport's clock (virtual for the in-process sim).
  virtual std::uint64_t now_us() = 0;
  // Datagrams keep frame boundaries; streams do not.
  virtual bool datagram() const = 0;
  // The client address a request carries: U (UART/UDP client) or P
  // (Topotek network client).
  virtual char client_address() const = 0;
  virtual void send(std::string_view bytes) = 0;
  // Waits until bytes arrive (true, `out` holds them) or `deadline_us`
  // passes (false). Throws TransportError.
  virtual bool receive(std::uint64_t deadline_us, std::string& out) = 0;
  // When the bytes receive() gave last arrived, on now_us()'s clock: the
  // kernel's time of the datagram over UDP (not when the runner got to
  // reading it), else when receive() returned.
  virtual std::uint64_t arrived_us() { return now_us(); }
  // For the pcap of the run.
  virtual pcapio::Endpoint local() const { return {}; }
  virtual pcapio::Endpoint remote() const { return {}; }
  virtual bool tcp() const { return false; }
  virtual std::string describe() const = 0;
  // Restarts the device when the transport can (the in-process topsim);
  // false when it cannot (a real device: topconf fuzz --restart-cmd).
  virtual bool restart() { return false; }
};

// An in-process topsim on a virtual clock: time advances only while the
// runner waits, straight to the next event, so runs are fast and exactly
// repeatable.
class SimTransport : public Transport {
 public:
  SimTransport(top::Model model, topsim::FaultConfig faults = {}, std::uint64_t seed = 1,
               topsim::Link link = topsim::Link::network,
               top::Profile profile = top::Profile::field);
  std::uint64_t now_us() override { return now_; }
  bool datagram() const override { return link_ == topsim::Link::network; }
  char client_address() const override;
  void send(std::string_view bytes) override;
  bool receive(std::uint64_t deadline_us, std::string& out) override;
  std::string describe() const override;
  // A power cycle: the device's state as at start, crash and hang cleared.
  bool restart() override;
  topsim::Device& device() noexcept { return device_; }

 private:
  // Queues `frames`, each `copies` times (sim/fanout.hpp).
  void schedule(const std::vector<std::string>& frames, std::size_t copies = 1);
  // How many copies of a frame sent to `ports` reach this client.
  std::size_t copies_to_us(const std::vector<std::uint16_t>& ports) const;
  topsim::Link link_;
  topsim::DeviceOptions options_;
  topsim::Device device_;
  topsim::FaultInjector faults_;
  top::StreamDecoder decoder_;
  std::uint64_t now_ = 1000000;
  std::uint64_t seq_ = 0;
  struct Pending {
    std::uint64_t at;
    std::uint64_t seq;
    std::string bytes;
  };
  std::deque<Pending> queue_;  // kept sorted by (at, seq)
  // The datagrams' routes (sim/fanout.hpp), the client asking from the
  // port a UDP client of the model binds (top::client_port, as topconf
  // does; another when the model has none): each frame arrives as many
  // times as the route names that port.
  topsim::Fanout fanout_;
  std::uint16_t own_port_ = 0;
  std::uint64_t line_busy_until_ = 0;  // stream links write one thing at a time
  std::uint64_t last_rx_ = 0;          // for the quiet flush of decoder_
  topsim::Intake intake() { return topsim::Intake{device_, link_, &faults_}; }
};

// Parses udp://HOST:PORT, tcp://HOST:PORT, serial:DEVICE[@BAUD] and opens
// it. `local_port` binds the UDP client (Topotek devices answer to 9004; 0
// an ephemeral port), on the target's own address for a loopback target
// (the loopback addresses of one machine are separate hosts), else on every
// address. The UDP socket is not connected: it sends to HOST:PORT and takes
// what comes from any port of HOST (top::replies_reach_host: a device may
// answer from a port of its own), nothing from other hosts. Throws
// TransportError naming the target.
std::unique_ptr<Transport> open_transport(const std::string& target, top::Model model,
                                          int local_port = -1);

// What topconf run and topconf fuzz test: with `sim`, an in-process topsim
// with the faults of `sim_faults` (topsim's --fault syntax) and `sim_seed`;
// otherwise open_transport(target), bound to `bind_port` or, for UDP, to the
// port the model answers to (-1). The in-process topsim is on `sim_link`
// (a serial line: topsim::Link::uart). Throws TransportError naming the bad
// --sim-fault or target.
std::unique_ptr<Transport> open_target(bool sim, const std::string& target, top::Model model,
                                       const std::string& sim_faults, std::uint64_t sim_seed,
                                       int bind_port,
                                       topsim::Link sim_link = topsim::Link::network);

}  // namespace topconf
