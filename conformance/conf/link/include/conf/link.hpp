// The tester's side of a link, shared by the runner and the fuzzer: bytes
// sent and received go to the pcap, received bytes through the stream
// decoder to frames.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <string_view>

#include "conf/transport.hpp"
#include "pcapio/writer.hpp"
#include "top/catalog.hpp"
#include "top/stream.hpp"

namespace topconf {

struct Received {
  top::Frame frame;
  std::uint64_t t_us = 0;      // when its bytes arrived
  bool after_garbage = false;  // bytes that belong to no frame came before it
};

// Whether the device of dialect `d` pushes frames of `ident` (GAC, GIC...)
// rather than answering with them (top/device.hpp's streams).
bool is_push(top::Dialect d, std::string_view ident);

class FrameLink {
 public:
  // At most `max_queued` frames wait; an older one makes room for a newer.
  FrameLink(Transport& t, pcapio::Recorder* pcap, std::size_t max_queued)
      : t_(t), pcap_(pcap), max_queued_(max_queued) {}

  std::uint64_t now() { return t_.now_us(); }
  void send(std::string_view bytes);

  // Next frame before `deadline`; false on timeout.
  bool next(std::uint64_t deadline, Received& out);
  // Forgets the frames already decoded.
  void clear() { frames_.clear(); }

  // Told of every chunk received and of every run of garbage (its length).
  std::function<void(std::string_view)> on_chunk;
  std::function<void(std::size_t)> on_garbage;

 private:
  void collect();

  Transport& t_;
  pcapio::Recorder* pcap_;
  std::size_t max_queued_;
  top::StreamDecoder dec_;
  std::deque<Received> frames_;
  bool garbage_ = false;
};

}  // namespace topconf
