// topdump serial: one or two serial ports (8N1) until Ctrl-C.
#include <string>
#include <vector>

#include "capture/live.hpp"
#include "common.hpp"

namespace topdump {

namespace {

struct SerialCommand {
  std::vector<std::string> devices;
  unsigned baud = 115200;

  void declare(CLI::App& sub) {
    sub.add_option("--baud", baud, "baud rate")->check(CLI::Range(50u, 4000000u));
    add_taps(sub, "DEVICE", devices,
             "serial device, e.g. /dev/ttyUSB0; two devices are two taps of one UART, one per "
             "direction, read as one conversation");
  }
  int run(const Common& c) const;
};

int SerialCommand::run(const Common& c) const {
  return run_live_input(
      c, devices[0],
      [&](Analyzer& a, SourceOptions&, const std::atomic<bool>& stop, std::string& err) {
        return read_serial_ports(devices, baud, a, stop, err);
      });
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> serial_command(CLI::App& app) {
  return make_command<SerialCommand>(app, CommandId::serial);
}

}  // namespace topdump
