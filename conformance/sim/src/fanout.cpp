#include "sim/fanout.hpp"

namespace topsim {

std::vector<std::uint16_t> Fanout::request(std::uint16_t port, bool new_host) {
  if (new_host) last_other_ = 0;
  last_asker_ = port;
  if (port != client_) last_other_ = port;
  return to(port);
}

std::vector<std::uint16_t> Fanout::push() const {
  if (last_asker_ == 0) return {};
  return to(last_asker_);
}

std::vector<std::uint16_t> Fanout::to(std::uint16_t asker) const {
  std::vector<std::uint16_t> out;
  if (traits_.fan_out && last_other_ != 0) out.push_back(last_other_);
  if (client_ != 0) {
    out.push_back(client_);
    if (traits_.duplicate) out.push_back(client_);
  }
  if (out.empty()) out.push_back(asker);
  return out;
}

}  // namespace topsim
