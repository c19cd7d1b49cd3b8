// topdump serial: one or two serial ports (8N1) until Ctrl-C.
#include <string>
#include <vector>

#include "capture/live.hpp"
#include "common.hpp"

namespace topdump {

namespace {

class SerialCommand : public CommonCommand {
 public:
  explicit SerialCommand(CLI::App& app)
      : CommonCommand(app, "serial", "Decode a serial port as bytes arrive (8N1); Ctrl-C ends") {
    add_common(sub_, c_, true, false);
    sub_->add_option("--baud", baud_, "baud rate")->check(CLI::Range(50u, 4000000u));
    sub_->add_option("DEVICE", devices_,
                     "serial device, e.g. /dev/ttyUSB0; two devices are two taps of one UART, one "
                     "per direction, read as one conversation")
        ->required()
        ->expected(1, 2);
    sub_->footer(output_help() +
                 "Events are printed as they are decoded; Ctrl-C prints the statistics and ends.\n"
                 "Examples:\n"
                 "  topdump serial /dev/ttyUSB0\n"
                 "  topdump serial --baud 57600 --model c12 /dev/ttyUSB0\n"
                 "  topdump serial /dev/ttyUSB0 /dev/ttyUSB1   # one tap per direction");
  }
  int run() override;

 private:
  std::vector<std::string> devices_;
  unsigned baud_ = 115200;
};

int SerialCommand::run() {
  return run_live_input(
      c_, devices_[0],
      [&](Analyzer& a, SourceOptions&, const std::atomic<bool>& stop, std::string& err) {
        return read_serial_ports(devices_, baud_, a, stop, err);
      });
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> serial_command(CLI::App& app) {
  return std::make_unique<SerialCommand>(app);
}

}  // namespace topdump
