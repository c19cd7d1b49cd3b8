// What the in-process topsim device tests share (device_faults_test.cpp,
// drive_faults_test.cpp): a fault spec parsed, and a request answered.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "sim/device.hpp"
#include "sim/faults.hpp"
#include "top/frame.hpp"

// `spec` as topsim --fault parses it; a spec it rejects fails the test.
inline topsim::FaultConfig faults_of(const std::string& spec) {
  std::string err;
  auto f = topsim::parse_faults(spec, err);
  EXPECT_TRUE(f.has_value()) << spec << ": " << err;
  return f.value_or(topsim::FaultConfig{});
}

// The frames device `d` answers `body` (its checksum added) with over the
// network at `t` us.
inline std::vector<top::Frame> ask(topsim::Device& d, const std::string& body, std::uint64_t t) {
  std::vector<top::Frame> v;
  for (const std::string& s :
       topsim::handle_datagram(d, top::with_checksum(body), topsim::Link::network, t))
    v.push_back(top::parse_exact(s).frame);
  return v;
}
