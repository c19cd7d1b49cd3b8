// The one path from received bytes to the device: decode, admit (the fault
// injector's firmware faults), handle. The server's UDP, TCP and line
// transports, topconf's in-process transport and the fuzz target all go
// through it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sim/device.hpp"
#include "sim/faults.hpp"
#include "top/stream.hpp"

namespace topsim {

// Where decoded frames go: a device on a link, behind an optional fault
// injector (null: every frame is admitted).
struct Intake {
  Device& device;
  Link link;
  FaultInjector* faults = nullptr;

  // Hands every frame `dec` holds decoded to the device at `now_us` (the
  // ones the fault injector admits) and appends the device's frames to
  // `out`; `received` (optional) gets the request frames. Returns the
  // number of frames decoded.
  std::size_t drain(top::StreamDecoder& dec, std::uint64_t now_us, std::vector<std::string>& out,
                    std::vector<top::Frame>* received = nullptr) const;
  // Feeds `bytes` to `dec`, one whole datagram (`datagram`; the decoder is
  // reset after it) or more of a stream (frames wait for their end), then
  // drain()s it.
  std::size_t take(top::StreamDecoder& dec, std::string_view bytes, bool datagram,
                   std::uint64_t now_us, std::vector<std::string>& out,
                   std::vector<top::Frame>* received = nullptr) const;
};

// Frames from the bytes of one connection (stream) or one datagram each.
class Session {
 public:
  Session(Device& device, Link link, bool datagram);
  // Decodes `bytes`, lets the device handle every frame, appends replies.
  // `received` (optional) gets the request frames.
  void feed(std::string_view bytes, std::uint64_t now_us, std::vector<std::string>& out,
            std::vector<top::Frame>* received = nullptr);

 private:
  Intake intake_;
  bool datagram_;
  top::StreamDecoder decoder_;
};

}  // namespace topsim
