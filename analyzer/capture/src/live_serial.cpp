// Live serial ports through Asio: one tap, or two taps of one UART.
#include <array>
#include <asio.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "capture/live.hpp"
#include "capture/time.hpp"
#include "log_reader.hpp"

namespace topdump {

bool read_serial_ports(const std::vector<std::string>& devices, unsigned baud, CaptureSink& a,
                       const std::atomic<bool>& stop, std::string& error) {
  asio::io_context io;
  struct Tap {
    asio::serial_port port;
    Endpoint src, dst;
    std::array<char, 4096> buf{};
    std::uint64_t chunk_no = 0, offset = 0;
  };
  std::vector<std::unique_ptr<Tap>> taps;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const std::string& device = devices[i];
    auto t = std::make_unique<Tap>(Tap{asio::serial_port(io), named(device),
                                       named(devices.size() == 2 ? devices[1 - i] : "peer")});
    asio::serial_port& port = t->port;
    asio::error_code ec;
    port.open(device, ec);
    if (ec) {
      error = device + ": " + ec.message();
      return false;
    }
    port.set_option(asio::serial_port_base::baud_rate(baud), ec);
    if (!ec) port.set_option(asio::serial_port_base::character_size(8), ec);
    if (!ec)
      port.set_option(asio::serial_port_base::parity(asio::serial_port_base::parity::none), ec);
    if (!ec)
      port.set_option(asio::serial_port_base::stop_bits(asio::serial_port_base::stop_bits::one),
                      ec);
    if (!ec)
      port.set_option(
          asio::serial_port_base::flow_control(asio::serial_port_base::flow_control::none), ec);
    if (ec) {
      error = device + ": cannot configure " + std::to_string(baud) + " 8N1: " + ec.message();
      return false;
    }
    taps.push_back(std::move(t));
  }
  // A frame is held until the line has been quiet for kSerialQuiet: a CR/LF
  // that follows within it belongs to the frame (an FTDI adapter delivers
  // what it has every 16 ms, its default latency timer).
  using clock = std::chrono::steady_clock;
  clock::time_point last_rx = clock::now();
  bool held = false;  // bytes arrived since the last flush
  asio::steady_timer tick(io);
  bool failed = false;
  std::size_t open = taps.size();
  std::function<void()> arm_tick = [&]() {
    tick.expires_after(std::chrono::milliseconds(10));
    tick.async_wait([&](const asio::error_code& e) {
      if (e) return;
      if (stop.load()) {
        for (auto& t : taps) {
          asio::error_code ignored;
          t->port.cancel(ignored);
        }
        return;
      }
      if (held && clock::now() - last_rx >= kSerialQuiet) {
        a.flush_streams();
        held = false;
      }
      arm_tick();
    });
  };
  std::function<void(Tap&)> arm_read = [&](Tap& t) {
    t.port.async_read_some(asio::buffer(t.buf), [&](const asio::error_code& e, std::size_t n) {
      if (e) {
        if (e != asio::error::operation_aborted && !stop.load()) {
          error = t.src.name + ": " + e.message();
          failed = true;
          for (auto& u : taps) {
            asio::error_code ignored;
            u->port.cancel(ignored);
          }
        }
        if (--open == 0) tick.cancel();
        return;
      }
      ++t.chunk_no;
      last_rx = clock::now();
      held = true;
      a.record(true);
      a.chunk(now_us(), Transport::serial, t.src, t.dst, std::string_view(t.buf.data(), n),
              t.chunk_no, t.offset);
      t.offset += n;
      arm_read(t);
    });
  };
  for (auto& t : taps) arm_read(*t);
  arm_tick();
  io.run();
  return !failed;
}

}  // namespace topdump
