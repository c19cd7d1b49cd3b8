// placeholder-identity: the device's identity reply (model name, serial
// number, version: top::is_identity_reply) is a factory placeholder
// (top::is_placeholder_identity): 000000000, 123, 1.2.3, Unknown.
#pragma once

#include <array>
#include <optional>

#include "diagnoses/case.hpp"

namespace topdump::diag {

class IdentityWatch {
 public:
  static constexpr std::array<top::Diagnosis, 1> codes = {top::Diagnosis::placeholder_identity};
  void reply(top::Dialect d, std::string_view ident, std::string_view data, std::uint64_t n,
             std::int64_t ts, int dir) {
    if (top::is_identity_reply(d, ident)) placeholder(ident, data, n, ts, dir);
  }
  std::optional<Found> verdict() const;

 private:
  void placeholder(std::string_view ident, std::string_view data, std::uint64_t n, std::int64_t ts,
                   int dir);
  Case c_;
  std::string value_;  // the first placeholder, at most 32 chars
};

}  // namespace topdump::diag
