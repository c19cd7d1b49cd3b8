// topdump live: live traffic on an interface (libpcap) until Ctrl-C.
#include <iostream>
#include <string>
#include <vector>

#include "capture/live.hpp"
#include "common.hpp"

namespace topdump {

namespace {

struct LiveOptions {
  Common c;
  std::string iface;
  std::vector<std::string> bpf;
};

int run_live(const LiveOptions& o) {
  Setup s;
  std::string err;
  if (!setup(o.c, s, err)) {
    std::cerr << "topdump live: " << err << "\n";
    return 2;
  }
  Out out(stdout, true);
  auto sink = make_sink(o.c, out, err);
  if (!sink) {
    std::cerr << "topdump live: " << err << "\n";
    return 2;
  }
  Tee tee(*sink, o.iface);
  Analyzer a(s.aopts, tee);
  a.set_filter(s.filter);
  std::string bpf;
  for (const auto& w : o.bpf) bpf += (bpf.empty() ? "" : " ") + w;
  install_signals();
  bool perm = false;
  if (!capture_live(o.iface, bpf, a, s.sopts, g_stop, err, perm)) {
    std::cerr << "topdump live: " << err << (perm ? " (capturing needs root or CAP_NET_RAW)" : "")
              << "\n";
    return 2;
  }
  a.finish();
  out.flush();
  print_final_stats(o.c, a);
  return status_of(a);
}

}  // namespace

Run add_live_command(CLI::App& app) {
  auto o = std::make_shared<LiveOptions>();
  CLI::App* sub =
      app.add_subcommand("live", "Decode live traffic on an interface (libpcap); Ctrl-C ends");
  add_common(sub, o->c, true);
  sub->add_option("-i,--interface", o->iface, "interface, e.g. eth0 or lo")->required();
  sub->add_option("BPF", o->bpf, "capture filter, e.g. udp port 5000")->default_str("");
  sub->footer(output_help() +
              "Events are printed as they are decoded; Ctrl-C prints the statistics and ends.\n"
              "Examples:\n"
              "  sudo topdump live -i eth0\n"
              "  sudo topdump live -i lo --json udp port 5000");
  return [o, sub]() { return sub->parsed() ? run_live(*o) : -1; };
}

}  // namespace topdump
