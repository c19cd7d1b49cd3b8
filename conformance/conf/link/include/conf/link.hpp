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
#include "top/device.hpp"
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

// Whether the device frame `f` (a reply, or a push) is addressed as an
// answer to a request from `src` to `dst`: the addresses swapped (SkyDroid
// 2.3.1), or in the request's order where the device's recorded form
// (top/device.hpp) says so (the SkyDroid 4.22 SLR example).
bool reply_addressed(top::Dialect d, top::Model m, const top::Frame& f, char src, char dst);
// The recorded form (top/device.hpp) a device frame matches, as a reply or
// a push by its identifier, or null.
const top::DeviceForm* recorded_form_of(top::Dialect d, top::Model m, const top::Frame& f);

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

  // Told of every write sent, every chunk received and every run of
  // garbage (its length).
  std::function<void(std::string_view)> on_send;
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
