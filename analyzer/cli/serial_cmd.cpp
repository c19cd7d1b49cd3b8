// topdump serial: one or two serial ports (8N1) until Ctrl-C.
#include <iostream>
#include <string>
#include <vector>

#include "capture/live.hpp"
#include "common.hpp"

namespace topdump {

namespace {

struct SerialOptions {
  Common c;
  std::vector<std::string> devices;
  unsigned baud = 115200;
};

int run_serial(const SerialOptions& o) {
  Setup s;
  std::string err;
  if (!setup(o.c, s, err)) {
    std::cerr << "topdump serial: " << err << "\n";
    return 2;
  }
  Out out(stdout, true);
  auto sink = make_sink(o.c, out, err);
  if (!sink) {
    std::cerr << "topdump serial: " << err << "\n";
    return 2;
  }
  Tee tee(*sink, o.devices[0]);
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  install_signals();
  if (!read_serial_ports(o.devices, o.baud, a, g_stop, err)) {
    std::cerr << "topdump serial: " << err << "\n";
    return 2;
  }
  a.finish();
  out.flush();
  print_final_stats(o.c, a);
  return status_of(a);
}

}  // namespace

Run add_serial_command(CLI::App& app) {
  auto o = std::make_shared<SerialOptions>();
  CLI::App* sub =
      app.add_subcommand("serial", "Decode a serial port as bytes arrive (8N1); Ctrl-C ends");
  add_common(sub, o->c, true, false);
  sub->add_option("--baud", o->baud, "baud rate")->check(CLI::Range(50u, 4000000u));
  sub->add_option("DEVICE", o->devices,
                  "serial device, e.g. /dev/ttyUSB0; two devices are two taps of one UART, one "
                  "per direction, read as one conversation")
      ->required()
      ->expected(1, 2);
  sub->footer(output_help() +
              "Events are printed as they are decoded; Ctrl-C prints the statistics and ends.\n"
              "Examples:\n"
              "  topdump serial /dev/ttyUSB0\n"
              "  topdump serial --baud 57600 --model c12 /dev/ttyUSB0\n"
              "  topdump serial /dev/ttyUSB0 /dev/ttyUSB1   # one tap per direction");
  return [o, sub]() { return sub->parsed() ? run_serial(*o) : -1; };
}

}  // namespace topdump
