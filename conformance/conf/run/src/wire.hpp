// The runner's side of the link (private to conf/run/): frames, and the
// case's transcript of everything sent, received and noted.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "conf/link.hpp"
#include "conf/probe.hpp"
#include "conf/runner.hpp"

namespace topconf::detail {

class Wire {
 public:
  Wire(Transport& t, const Matrix& m, const RunOptions& o, std::uint64_t t0)
      : link_(t, o.pcap, o.max_frames_per_step), m_(m), o_(o), t0_(t0) {
    link_.on_send = [this](std::string_view bytes) { log('>', std::string(bytes)); };
    link_.on_chunk = [this](std::string_view chunk) { log('<', std::string(chunk)); };
    link_.on_garbage = [this](std::size_t n) {
      note("garbage: " + std::to_string(n) + " byte(s) that belong to no frame");
    };
    // A device that sends each datagram to several of the client's ports
    // (top/device.hpp fan_out, duplicate_to_client_port): a copy is that
    // datagram again, neither a frame nor an answer of its own.
    link_.accept_copies(sends_copies(m.model));
    link_.on_copy = [this](std::string_view bytes, std::uint64_t after_us) {
      log('<', std::string(bytes));
      note("a copy of the datagram " + std::to_string(after_us) + " us before (fan-out)");
    };
  }

  Wire(const Wire&) = delete;  // the link calls back into this one
  Wire& operator=(const Wire&) = delete;

  void begin_case(CaseResult* r) { rec_ = r; }
  std::uint64_t now() { return link_.now(); }

  void note(std::string s) { log('!', std::move(s)); }
  void send(std::string_view bytes) { link_.send(bytes); }

  // Next frame before `deadline`; false on timeout. Garbage is noted.
  bool next(std::uint64_t deadline, Received& out) { return link_.next(deadline, out); }

  // Discards whatever already arrived (late answers of a previous step).
  void drain() {
    Received r;
    const std::uint64_t d = now();
    std::size_t n = 0, late = 0;
    while (n < o_.max_frames_per_step && next(d, r)) {
      ++n;
      const std::string_view id = r.frame.ident_view();
      if (!is_push(m_.dialect, id)) ++late;  // pushes (the stream table's) are expected
    }
    link_.clear();
    if (late > 0)
      note("discarded " + std::to_string(late) + " late frame(s) before the next exchange");
  }

  // The liveness probe, once, between drains.
  ProbeHeard probe(const Probe& p) {
    drain();
    const ProbeHeard heard = probe_once(link_, p, std::uint64_t{m_.probe_timeout_ms} * 1000);
    if (heard == ProbeHeard::answer) drain();
    return heard;
  }

 private:
  void log(char dir, std::string bytes) {
    if (!rec_) return;
    if (rec_->transcript.size() >= o_.max_transcript) {
      ++rec_->dropped_exchanges;
      return;
    }
    if (bytes.size() > 512) bytes = bytes.substr(0, 512) + "...";
    rec_->transcript.push_back(Exchange{now() - t0_, dir, std::move(bytes)});
  }

  FrameLink link_;
  const Matrix& m_;
  const RunOptions& o_;
  std::uint64_t t0_;
  CaseResult* rec_ = nullptr;
};

}  // namespace topconf::detail
