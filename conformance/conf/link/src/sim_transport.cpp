// topconf's in-process topsim on a virtual clock.
#include <algorithm>

#include "conf/transport.hpp"
#include "sim/intake.hpp"
#include "top/device.hpp"

namespace topconf {

SimTransport::SimTransport(top::Model model, topsim::FaultConfig faults, std::uint64_t seed,
                           topsim::Link link, top::Profile profile)
    : link_(link),
      options_([&] {
        topsim::DeviceOptions o;
        o.profile = profile;
        o.swap_addresses = !faults.no_swap;
        o.tmp_quirk = faults.tmp_quirk;
        o.faults = faults.device;
        return o;
      }()),
      device_(model, options_),
      faults_(faults, seed),
      fanout_(device_.udp_traits(), top::client_port(model)),
      // a port of the client's host that no device port table names
      own_port_(top::client_port(model) ? top::client_port(model) : 40000) {}

bool SimTransport::restart() {
  device_ = topsim::Device(device_.model(), options_);
  faults_.restart();
  queue_.clear();
  decoder_.reset();
  fanout_ = topsim::Fanout(device_.udp_traits(), fanout_.client_port());
  return true;
}

std::size_t SimTransport::copies_to_us(const std::vector<std::uint16_t>& ports) const {
  // a serial line has no ports: one copy
  if (!datagram()) return 1;
  return static_cast<std::size_t>(std::count(ports.begin(), ports.end(), own_port_));
}

char SimTransport::client_address() const { return top::client_address(device_.dialect(), link_); }

std::string SimTransport::describe() const {
  return std::string("in-process topsim ") + std::string(top::to_string(device_.model()));
}

void SimTransport::schedule(const std::vector<std::string>& frames, std::size_t copies) {
  std::vector<topsim::Emission> em;
  for (const auto& f : frames) faults_.apply(f, link_ == topsim::Link::uart, em);
  if (copies != 1) {
    // the copies of each emission, at its time (sim/fanout.hpp)
    std::vector<topsim::Emission> all;
    for (const auto& e : em)
      for (std::size_t i = 0; i < copies; ++i) all.push_back(e);
    em = std::move(all);
  }
  for (auto& e : em) {
    std::uint64_t at = now_ + e.delay_us;
    if (!datagram()) {
      // One write at a time on a line: a split frame is not interleaved.
      at = std::max(at, line_busy_until_);
      line_busy_until_ = at;
    }
    Pending p{at, seq_++, std::move(e.bytes)};
    auto it =
        std::upper_bound(queue_.begin(), queue_.end(), p, [](const Pending& a, const Pending& b) {
          return a.at != b.at ? a.at < b.at : a.seq < b.seq;
        });
    queue_.insert(it, std::move(p));
  }
  // A device that never drains would grow without bound; a real link
  // drops what its buffers cannot hold.
  while (queue_.size() > 100000) queue_.pop_back();
}

void SimTransport::send(std::string_view bytes) {
  if (datagram()) decoder_.reset();
  last_rx_ = now_;
  std::vector<std::string> replies;
  intake().take(decoder_, bytes, datagram(), now_, replies);
  schedule(replies, datagram() ? copies_to_us(fanout_.request(own_port_)) : 1);
}

bool SimTransport::receive(std::uint64_t deadline_us, std::string& out) {
  for (;;) {
    const std::uint64_t t_queue = queue_.empty() ? UINT64_MAX : queue_.front().at;
    const std::uint64_t t_dev = faults_.hung() ? UINT64_MAX : device_.next_timer();
    // The device decides on held bytes once the line has been quiet.
    const std::uint64_t t_quiet = !datagram() && decoder_.buffered() > 0
                                      ? last_rx_ + std::uint64_t{top::quiet_line_ms} * 1000
                                      : UINT64_MAX;
    const std::uint64_t t = std::min({t_queue, t_dev, t_quiet});
    if (t > deadline_us) {
      now_ = std::max(now_, deadline_us);
      return false;
    }
    now_ = std::max(now_, t);
    if (t == t_quiet && t < t_queue) {
      const std::size_t held = decoder_.buffered();
      decoder_.settle();
      std::vector<std::string> replies;
      intake().drain(decoder_, now_, replies);
      // a frame cut short keeps waiting: the line's bytes are all here, so
      // it is junk; drop it as a device whose UART timed out would
      if (decoder_.buffered() >= held) decoder_.reset();
      schedule(replies);
      continue;
    }
    if (t_queue <= t_dev) {
      out = std::move(queue_.front().bytes);
      queue_.pop_front();
      return true;
    }
    std::vector<std::string> frames;
    device_.poll(now_, frames);
    schedule(frames, copies_to_us(fanout_.push()));
  }
}

}  // namespace topconf
