// The wire of one case as the checks read it: every chunk or datagram the
// device received or sent, cut into frames and decoded (private to drive/).
#pragma once

#include <mutex>
#include <string_view>
#include <vector>

#include "drive/record.hpp"
#include "top/catalog.hpp"
#include "top/stream.hpp"

namespace topconf::drive::detail {

class WireTap {
 public:
  WireTap(top::Model model, bool datagrams, bool field);
  // One chunk (a datagram on UDP) at `t` seconds: from the driver (`in`)
  // or from the device. Thread-safe (the server's thread calls it).
  void take(double t, bool in, std::string_view bytes);
  // The frames so far, in arrival order.
  std::vector<WireFrame> frames() const;

 private:
  void drain(double t, bool in, top::StreamDecoder& decoder);
  top::Model model_;
  bool datagrams_, field_;
  mutable std::mutex mu_;
  top::StreamDecoder in_, out_;
  std::vector<WireFrame> frames_;
};

}  // namespace topconf::drive::detail
