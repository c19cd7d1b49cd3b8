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

// Whether a device of `m` may send each datagram more than once to the
// same client port (the traits fan_out, duplicate_to_client_port of a real
// Topotek camera): the copies are one datagram, not two answers.
bool sends_copies(top::Model m);

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

  // Takes a datagram that repeats one received within
  // top::fan_out_copy_window_us before it, with no request sent between
  // them, as a copy of that one (sends_copies): told to on_copy, recorded,
  // never decoded again. Two answers with the same bytes to two requests
  // are two answers, however close: before a request leaves, the copies of
  // the last datagram are waited for (until the window after it is over).
  void accept_copies(bool on) { copies_ = on; }

  // Told of every write sent, every chunk received and every run of
  // garbage (its length).
  std::function<void(std::string_view)> on_send;
  std::function<void(std::string_view)> on_chunk;
  std::function<void(std::size_t)> on_garbage;
  // Told of a copy and how long after the datagram it repeats it arrived.
  std::function<void(std::string_view, std::uint64_t)> on_copy;

 private:
  // One chunk received: recorded, and decoded unless it is a copy.
  void take(const std::string& chunk);
  void collect(std::uint64_t at);
  // Whether `chunk`, arrived at `at`, repeats a datagram of the last
  // top::fan_out_copy_window_us (and since when); else it is remembered.
  bool copy_of_recent(const std::string& chunk, std::uint64_t at, std::uint64_t& after);

  Transport& t_;
  bool copies_ = false;
  struct Recent {
    std::string bytes;
    std::uint64_t at;
  };
  std::deque<Recent> recent_;
  pcapio::Recorder* pcap_;
  std::size_t max_queued_;
  top::StreamDecoder dec_;
  std::deque<Received> frames_;
  bool garbage_ = false;
};

}  // namespace topconf
