// What a harness asks of a running topsim::Server (topconf drive,
// docs/DRIVE.md): the device's truth, a change of case in place, and the
// timed power cycle of the reboot= fault (armed by the constructor).
#include <condition_variable>
#include <memory>
#include <mutex>

#include "server_impl.hpp"

namespace topsim {
namespace {

// Runs `fn` on `io`'s thread and waits for it, up to 1 s. A call given up
// on never runs later: `fn` may hold references to the caller's frame.
bool run_on(asio::io_context& io, std::function<void()> fn) {
  struct State {
    std::mutex mu;
    std::condition_variable cv;
    bool done = false, abandoned = false;
  };
  auto st = std::make_shared<State>();
  asio::post(io, [fn = std::move(fn), st] {
    std::lock_guard lock(st->mu);
    if (st->abandoned) return;
    fn();
    st->done = true;
    st->cv.notify_all();
  });
  std::unique_lock lock(st->mu);
  if (!st->cv.wait_for(lock, std::chrono::seconds(1), [&] { return st->done; }))
    st->abandoned = true;
  return st->done;
}

}  // namespace

void Server::Impl::arm_reboot() {
  if (cfg.faults.reboot_us == 0) return;
  reboot_timer.expires_at(start + std::chrono::microseconds(cfg.faults.reboot_us));
  reboot_timer.async_wait([this](std::error_code ec) {
    if (!ec) restart();
  });
}

bool Server::visit(const std::function<void(const Device&, std::uint64_t)>& fn) {
  Impl& m = *impl_;
  return run_on(m.io, [&m, &fn] {
    const std::uint64_t now = m.now_us();
    m.device.advance(now);
    fn(m.device, now);
  });
}

bool Server::reconfigure(const FaultConfig& faults, const DeviceOptions& options) {
  Impl& m = *impl_;
  return run_on(m.io, [&m, faults, options] {
    m.cfg.faults = faults;
    m.cfg.device_options = options;
    m.faults = FaultInjector(faults, m.cfg.seed);
    m.device.reconfigure(m.device_options(), m.now_us());
    if (m.fanout) m.fanout.emplace(m.device.udp_traits(), m.fanout->client_port());
    m.reboot_timer.cancel();
    if (faults.reboot_us > 0) {
      // reboot= counts from the change of case.
      m.cfg.faults.reboot_us += m.now_us();
      m.arm_reboot();
    }
    m.arm_stream_timer();
  });
}

std::uint64_t Server::now_us() const { return impl_->now_us(); }

}  // namespace topsim
