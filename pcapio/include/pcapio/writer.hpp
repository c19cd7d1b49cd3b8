// Capture files: pcap written through libpcap (pcap_open_dead +
// pcap_dump_open), pcapng built here (libpcap 1.10 writes no pcapng, and
// the tests want several interfaces in one file), and the recorder topsim
// and topconf keep of their traffic.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "pcapio/endpoint.hpp"

struct pcap;
struct pcap_dumper;

namespace pcapio {

// A pcap file written through libpcap, microsecond timestamps.
class PcapWriter {
 public:
  PcapWriter(const std::string& path, int dlt, int snaplen = 65535);
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;
  bool ok() const { return dumper_ != nullptr; }
  // Why the file did not open ("" when it did).
  const std::string& error() const { return error_; }
  // Writes a packet; caplen < bytes.size() cuts it (as a snap length would);
  // `len`, when more than the bytes, is its length on the wire.
  void write(std::int64_t ts_us, std::string_view bytes, std::size_t caplen = SIZE_MAX,
             std::size_t len = 0);
  void flush();
  // Flushes and closes; false when a write or the close failed.
  bool finish();
  void close();

 private:
  pcap* p_ = nullptr;
  pcap_dumper* dumper_ = nullptr;
  std::string error_;
};

// A pcapng file (little-endian, microsecond timestamps): a section header,
// one interface block per link type, an enhanced packet block per packet.
struct NgPacket {
  std::uint32_t interface = 0;
  std::int64_t ts_us = 0;
  std::string bytes;
};
std::string pcapng(const std::vector<std::uint16_t>& linktypes,
                   const std::vector<NgPacket>& packets);

bool write_file(const std::string& path, std::string_view bytes);

// A capture file of one link type whose format follows its name: pcapng
// for "*.pcapng" (one interface, built here), pcap through libpcap (the
// PcapWriter above) for any other. topdump read -w writes through it.
class CaptureWriter {
 public:
  static bool is_pcapng(const std::string& path);
  CaptureWriter(const std::string& path, int dlt);
  ~CaptureWriter();
  CaptureWriter(const CaptureWriter&) = delete;
  CaptureWriter& operator=(const CaptureWriter&) = delete;
  // Whether the file opened (error() says why not).
  bool ok() const { return error_.empty() && (ng_ || pcap_); }
  const std::string& error() const { return error_; }
  // A packet of `bytes` captured at `ts_us`; `len` (when more) its length
  // on the wire.
  void write(std::int64_t ts_us, std::string_view bytes, std::size_t len = 0);
  // Flushes and closes; false, with error() naming the file and the cause,
  // when the file did not open or a write or the close failed.
  bool close();

 private:
  std::string path_;
  std::string error_;
  std::FILE* ng_ = nullptr;
  std::unique_ptr<PcapWriter> pcap_;
  std::string buf_;
  int failed_ = 0;  // errno of the first failed write
};

// What topsim and topconf send and receive, as Ethernet/IPv4/UDP (or TCP)
// packets between IPv4 endpoints with the real ports, stamped with the wall
// clock, so topdump and tcpdump decode it. Serial and pseudo-terminal
// traffic is recorded as UDP between 127.0.0.1 ports.
class Recorder {
 public:
  // Opens `path`; throws std::runtime_error naming the file.
  Recorder(const std::string& path, bool tcp);
  // One packet from `from` to `to` carrying `payload` (payloads past 65000
  // bytes in several packets).
  void write(const Endpoint& from, const Endpoint& to, std::string_view payload);
  void flush() { file_.flush(); }
  std::uint64_t packets() const noexcept { return packets_; }

 private:
  void packet(const Endpoint& from, const Endpoint& to, std::string_view payload);
  PcapWriter file_;
  bool tcp_ = false;
  std::uint32_t seq_a_ = 1000, seq_b_ = 50000;  // per direction (lower port first)
  std::uint16_t ip_id_ = 1;
  std::uint64_t packets_ = 0;
};

}  // namespace pcapio
