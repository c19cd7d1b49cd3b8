// topdump live: live traffic on an interface (libpcap) until Ctrl-C.
#include <string>
#include <vector>

#include "capture/live.hpp"
#include "common.hpp"

namespace topdump {

namespace {

class LiveCommand : public CommonCommand {
 public:
  explicit LiveCommand(CLI::App& app)
      : CommonCommand(app, "live", "Decode live traffic on an interface (libpcap); Ctrl-C ends") {
    add_common(sub_, c_, true);
    sub_->add_option("-i,--interface", iface_, "interface, e.g. eth0 or lo")->required();
    sub_->add_option("BPF", bpf_, "capture filter, e.g. udp port 5000")->default_str("");
    sub_->footer(output_help() +
                 "Events are printed as they are decoded; Ctrl-C prints the statistics and ends.\n"
                 "Examples:\n"
                 "  sudo topdump live -i eth0\n"
                 "  sudo topdump live -i lo --json udp port 5000");
  }
  int run() override;

 private:
  std::string iface_;
  std::vector<std::string> bpf_;
};

int LiveCommand::run() {
  std::string bpf;
  for (const auto& w : bpf_) bpf += (bpf.empty() ? "" : " ") + w;
  return run_live_input(
      c_, iface_,
      [&](Analyzer& a, SourceOptions& sopts, const std::atomic<bool>& stop, std::string& err) {
        bool perm = false;
        if (capture_live(iface_, bpf, a, sopts, stop, err, perm)) return true;
        if (perm) err += " (capturing needs root or CAP_NET_RAW)";
        return false;
      });
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> live_command(CLI::App& app) {
  return std::make_unique<LiveCommand>(app);
}

}  // namespace topdump
