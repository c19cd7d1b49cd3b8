// topdump live: live traffic on an interface (libpcap) until Ctrl-C.
#include <string>
#include <vector>

#include "capture/live.hpp"
#include "common.hpp"

namespace topdump {

namespace {

struct LiveCommand {
  std::string iface;
  std::vector<std::string> bpf;

  void declare(CLI::App& sub) {
    sub.add_option("-i,--interface", iface, "interface, e.g. eth0 or lo")->required();
    sub.add_option("BPF", bpf, "capture filter, e.g. udp port 5000")->default_str("");
  }
  int run(const Common& c) const;
};

int LiveCommand::run(const Common& c) const {
  std::string filter;
  for (const auto& w : bpf) filter += (filter.empty() ? "" : " ") + w;
  return run_live_input(
      c, iface,
      [&](Analyzer& a, SourceOptions& sopts, const std::atomic<bool>& stop, std::string& err) {
        bool perm = false;
        if (capture_live(iface, filter, a, sopts, stop, err, perm)) return true;
        if (perm) err += " (capturing needs root or CAP_NET_RAW)";
        return false;
      });
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> live_command(CLI::App& app) {
  return make_command<LiveCommand>(app, CommandId::live);
}

}  // namespace topdump
