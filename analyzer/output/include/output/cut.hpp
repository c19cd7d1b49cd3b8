// topdump read -w FILE: cuts the selected frames out of a capture into a
// new one (pcap, or pcapng for "*.pcapng"), through pcapio's CaptureWriter.
// From a pcap/pcapng source it writes the packets that carry the frames, as
// they were captured: the packet of a frame's first byte and, for TCP, the
// first later packet that holds the frame's last bytes (a TOP frame spans
// at most two segments but in rare cases; a third, middle one is not
// written). Packets are held, in order,
// until kHeldPackets / kHeldBytes are reached; a frame whose first packet
// left the hold before the frame was decoded (a TCP stream held longer than
// that) is counted in lost(). A serial source has no packets: each selected
// frame is written as an Ethernet/IPv4/UDP packet between 127.0.0.1 ports,
// one port per endpoint name from 40001 in order of appearance, stamped
// with the frame's time (0 when the log has none): the form topsim and
// topconf record serial traffic in, which topdump reads back.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "pcapio/writer.hpp"
#include "session/analyzer.hpp"

namespace topdump {

class Cutter : public Sink {
 public:
  static constexpr std::size_t kHeldPackets = 1u << 16;
  static constexpr std::size_t kHeldBytes = 64u << 20;
  static constexpr std::uint16_t kFirstSerialPort = 40001;
  Cutter(Sink& inner, std::string path) : inner_(inner), path_(std::move(path)) {}
  // A packet of the source, before it is dissected (SourceOptions::packet).
  void packet(int dlt, std::int64_t ts, std::string_view bytes, std::uint32_t len,
              std::uint64_t record);
  void frame(const FrameEvent& e) override;
  void garbage(const GarbageEvent& e) override { inner_.garbage(e); }
  void note(const NoteEvent& e) override { inner_.note(e); }
  // Writes what is held and closes the file; false with `error` when it
  // cannot be opened or written.
  bool finish(std::string& error);
  std::uint64_t written() const noexcept { return written_; }
  std::uint64_t lost() const noexcept { return lost_; }

 private:
  struct Held {
    std::uint64_t record;
    std::int64_t ts;
    std::string bytes;
    std::uint32_t len;
    bool keep;
  };
  void mark(std::uint64_t record);
  void evict();
  bool open(int dlt);
  Sink& inner_;
  std::string path_;
  std::unique_ptr<pcapio::CaptureWriter> w_;
  std::deque<Held> held_;
  std::size_t held_bytes_ = 0;
  bool packets_ = false;  // the source hands packets
  std::map<std::string, std::uint16_t> ports_;
  std::uint64_t written_ = 0, lost_ = 0;
};

}  // namespace topdump
