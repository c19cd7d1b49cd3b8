// topconf drivers: the driver profiles (conformance/drivers/), each with
// its models, link and sources; --json gives every fact.
#include <iostream>

#include "commands.hpp"
#include "drivers/compat.hpp"

namespace topconf::cli {

namespace {

struct Drivers {
  bool json = false;
  void declare(CLI::App& sub) {
    sub.add_flag("--json", json,
                 "every fact of each profile (link, cadence, frames sent, parsing, needs) with "
                 "its source");
  }
  int run() const;
};

int Drivers::run() const {
  if (json) {
    nlohmann::json all = nlohmann::json::array();
    for (const drivers::Profile& p : drivers::profiles()) all.push_back(drivers::to_json(p));
    std::cout << all.dump(2) << "\n";
    return 0;
  }
  for (const drivers::Profile& p : drivers::profiles()) {
    std::cout << p.name << ": " << p.title << "\n  models:";
    for (top::Model m : p.models) std::cout << " " << top::to_string(m);
    std::cout << "; link: " << drivers::to_string(p.link.kind);
    if (p.link.baud) std::cout << " " << p.link.baud << " baud";
    if (p.link.device_port) std::cout << " to port " << p.link.device_port;
    if (p.link.listen_port) std::cout << ", answers on " << p.link.listen_port;
    std::cout << "\n  needs:";
    for (const drivers::Need& n : p.needs)
      std::cout << " " << n.id << " (" << drivers::to_string(n.grade) << ")";
    std::cout << "\n";
    for (const drivers::Source& s : p.sources)
      std::cout << "  source: " << drivers::to_string(s) << "\n";
  }
  return 0;
}

}  // namespace

std::unique_ptr<topkit::cli::Subcommand> drivers_command(CLI::App& app) {
  return topkit::cli::make_subcommand<Drivers>(
      app, "drivers", "list the driver profiles topconf run --driver checks, with their sources");
}

}  // namespace topconf::cli
