// One conversation's state: its two directions, what each decodes, its
// pairing, streams and detectors, and what a device that answers the
// client's host did (HostLink). The stages of the session (session.hpp)
// work on it; the conversation table (conversation_table.hpp) holds it.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "diagnoses/silent_device.hpp"
#include "diagnoses/watch.hpp"
#include "session/events.hpp"
#include "session/pairing.hpp"
#include "session/stats.hpp"
#include "session/tcp_reassembly.hpp"
#include "top/detail/ring.hpp"
#include "top/stream.hpp"

namespace topdump {

// A chunk of a direction's byte stream: where its bytes came from.
struct Seg {
  std::uint64_t stream_off;
  std::uint64_t record;
  std::uint64_t rec_off;
  std::int64_t ts;
};

// Requests that went unanswered while the device said nothing: reported as
// one finding for the stretch (silent-device's when it decides so).
struct Silence {
  diag::SilentStretch stretch;
  Position pos;
  std::string single;  // the message when the stretch holds one request
  Note about;          // the first request's identifier and addresses
  // The device was not silent: it sent frames to another port of the
  // client's host (`elsewhere`, another conversation) meanwhile.
  Endpoint elsewhere;
  std::uint64_t elsewhere_conv = 0;
};

// The pair of ends a record went between, as the conversation table found
// it: a conversation's own pair, or another pair it takes (HostLink).
struct Route {
  Endpoint src, dst;
  std::string from, to;  // endpoint texts
  int dir = 0;           // the conversation's direction this pair goes in
};

// A direction's stream decoder, made at the first bytes fed to it: a TCP or
// serial direction feeds it, a UDP conversation's datagrams go through the
// session's one decoder (Analyzer::datagram), so most directions of a
// capture never need one (each is a heap block and 2 KB: the fuzz targets
// made two per conversation, docs/perf/fuzz-speed.md, "Issue 48: the
// per-conversation cost"). Until then it is a decoder that was fed nothing.
class LazyDecoder {
 public:
  void feed(std::string_view b) {
    if (!d_) d_.emplace();
    d_->feed(b);
  }
  bool next(top::StreamItem& out) { return d_ && d_->next(out); }
  void flush() {
    if (d_) d_->flush();
  }
  void finish() {
    if (d_) d_->finish();
  }
  void reset() {
    if (d_) d_->reset();
  }
  std::uint64_t fed() const noexcept { return d_ ? d_->fed() : 0; }

 private:
  std::optional<top::StreamDecoder> d_;
};

// One direction of a conversation: its own pair of ends (the Route), and
// what it decodes.
struct Direction : Route {
  // The pair the frames being decoded now went between: this one, or a
  // HostLink's (set per datagram).
  const Route* now = this;
  LazyDecoder dec;
  // The chunks whose bytes the decoder holds, oldest first (at most 4096).
  // A Ring, not a std::deque: a deque allocates two blocks as it is made,
  // and a conversation makes two directions, TCP or not.
  top::detail::Ring<Seg> segs;
  std::uint64_t base = 0;  // stream offset of the decoder's offset 0
  std::uint64_t last_record = 0;
  std::uint32_t index = 0;
  TcpReassembly tcp;  // TCP
  // repeats
  std::string last_req;
  std::int64_t last_req_ts = kNoTime;
  std::int64_t last_frame_ts = kNoTime;  // the last frame this direction sent
  bool sent_frame = false;
};

// What a conversation of a device that answers the client's host (not its
// port) keeps: the other pairs of ends it takes, and what the device did
// with them, for the notes at its end.
struct HostLink {
  Endpoint device;       // the end on the device's served port
  Endpoint client_host;  // the client's address, port 0
  top::Dialect dialect = top::Dialect::unknown;
  std::uint16_t client_port = 0;  // the dialect's client port (Topotek 9004), 0: none
  // The other pairs (a client port, the device's reply port) and their keys,
  // to forget them when the conversation closes.
  std::vector<std::unique_ptr<Route>> routes;
  std::vector<std::uint16_t> client_ports;  // that sent to the device (at most 16)
  std::vector<std::uint16_t> reply_ports;   // the device sent from, besides its own (at most 16)
  std::vector<std::uint16_t> copy_ports;    // copies went to (at most 16)
  // Adds port `p` to one of the three lists above: each port once, 16 at most.
  static void note_port(std::vector<std::uint16_t>& ports, std::uint16_t p) {
    if (ports.size() < 16 && std::find(ports.begin(), ports.end(), p) == ports.end())
      ports.push_back(p);
  }
  std::uint64_t device_frames = 0;    // frames of the device, copies aside
  std::uint64_t from_reply_port = 0;  // of them, sent from a reply port
  std::uint64_t copies = 0;           // copies of the device's frames
  std::uint64_t fanned = 0;           // frames of the device that had a copy
  // The first frame from a reply port, and the first copy: where the notes sit.
  std::uint64_t reply_port_n = 0, copy_n = 0;
  std::int64_t reply_port_ts = kNoTime, copy_ts = kNoTime;
  const Route* reply_port_at = nullptr;  // the ends they went between
  const Route* copy_at = nullptr;
  // The device's last frames, a copy compared with each: the deliveries of
  // two datagrams may interleave (a real Topotek camera sent a TRC, an OFT,
  // the TRC's copy, then the OFT's: PixEagle bench, 20260918T060610Z-
  // rotated-point 06:06:14.538870).
  struct Sent {
    std::string raw;
    std::int64_t ts = kNoTime;
    std::uint64_t n = 0;
    bool copied = false;
  };
  std::array<Sent, 4> recent{};
  std::size_t recent_next = 0;
  std::int64_t newest_ts = kNoTime;  // the newest of them
  std::uint64_t last_n = 0;          // the frame the copy at hand copies
  // The last reply reached another port than its request came from
  // (`asker`): whether a copy reaches that port decides.
  bool check = false;
  std::uint16_t asker = 0;
  std::uint64_t check_n = 0;  // the reply
  std::int64_t check_ts = kNoTime;
  Pending asked{};      // the request (its route, number, time, identifier)
  std::string reached;  // the endpoint the reply went to
  // The requests whose replies never reached the port that asked: one note.
  Silence elsewhere;
  std::string elsewhere_asker;
  const Route* elsewhere_at = nullptr;  // the first such request's pair of ends
};

struct Conversation {
  std::uint64_t id = 0;
  Transport transport{};
  Direction dir[2];
  bool has_dir1 = false;
  // The direction the device sends in (-1: not known yet): from the ports
  // (a well-known device port at one end), else from the first frame that
  // only a device sends (addressed to a client, or answering a request), or
  // the first stream switch (GAA, GIA, FAE) a client sends.
  int device_dir = -1;
  // A device whose frames reach any port of the client's host from any port
  // of its own (top::replies_reach_host: Topotek): every UDP datagram
  // between the two hosts belongs here (HostLink), null otherwise.
  std::unique_ptr<HostLink> link;
  Silence silence;
  top::DialectDetector det;
  std::uint32_t observed = 0;
  Pairing pairing;
  std::uint64_t last_used = 0;
  ConvStats st;
  // The conversation's diagnoses (analyzer/diagnoses/): last, a few KB of
  // state most frames touch little of, so that the fields every frame
  // uses stay on the cache lines next to each other.
  diag::Watch watch;
  // Below: what a reply or a frame of a host link touches, after the
  // state most frames use.
  // The slowest answer per identifier (at most 8 identifiers), whatever the
  // filter selects: how long after a request the capture must go on hearing
  // the device before the request is unanswered at its end.
  struct Slowest {
    // a slot per identifier by a hash of it, then the next free one: most
    // replies find theirs at once (docs/perf/decisions.md, "The slowest
    // answer per identifier")
    std::array<std::uint32_t, 8> key{};
    std::array<std::int64_t, 8> us{};
    static std::size_t home(std::uint32_t k) noexcept { return (k * 0x9E3779B1u) >> 29; }
    void add(std::uint32_t k, std::int64_t v) noexcept {
      for (std::size_t n = 0, i = home(k); n < key.size(); ++n, i = (i + 1) % key.size())
        if (key[i] == k || key[i] == 0) {
          key[i] = k;
          if (v > us[i]) us[i] = v;
          return;
        }
    }
    std::int64_t of(std::uint32_t k) const noexcept {
      for (std::size_t n = 0, i = home(k); n < key.size() && key[i]; ++n, i = (i + 1) % key.size())
        if (key[i] == k) return us[i];
      return -1;
    }
  } slowest;
  // Writes taken without a reply, as the device's rule says
  // (top::write_reply nothing), for the silent-writes note.
  std::uint64_t silent_writes = 0;
  std::string silent_idents;
  std::uint64_t silent_n = 0;  // the first of them
  std::int64_t silent_ts = kNoTime;
  const Route* silent_at = nullptr;
};

}  // namespace topdump
