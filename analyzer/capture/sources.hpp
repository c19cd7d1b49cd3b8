// Capture sources: pcap/pcapng files and live interfaces through libpcap,
// serial logs (raw, socat -v / -x -v, Saleae Logic 2 CSV, line log) and a
// live serial port through Asio. Each feeds an Analyzer.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "session/analyzer.hpp"

namespace topdump {

enum class Format : std::uint8_t { automatic, pcap, raw, socat, saleae, lines, pcapng };
std::optional<Format> format_from_string(std::string_view s);
std::string_view to_string(Format f) noexcept;

// Picks the format from the first bytes of a file.
Format detect_format(std::string_view head);

// Why a head that is no pcap/pcapng starts like one (a damaged capture,
// not a raw serial dump): the pcap version or the pcapng byte-order magic
// behind a bad magic number. nullopt otherwise.
std::optional<std::string> damaged_capture(std::string_view head);

// How many first bytes of an input open_input() reads for detection.
inline constexpr std::size_t kInputHead = 4096;

// An input opened for reading: a file, or stdin ("-"), a pipe, FIFO or
// terminal, whose first bytes are read for detection and handed out again.
struct Input {
  std::string name;                // the path, "stdin" for "-"
  std::unique_ptr<char[]> buffer;  // the FILE's buffer; outlives it
  std::FILE* file = nullptr;       // at byte 0 of the content
  std::string head;                // the first bytes (up to kInputHead)
  bool regular = false;            // a regular file (seekable, sized)
  std::uint64_t size = 0;          // regular files
  Input() = default;
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;
  ~Input() {
    if (file) std::fclose(file);
  }
};
// Opens `path` ("-": stdin). false with `error` naming the file (cannot
// open, a directory, a read error).
bool open_input(const std::string& path, Input& in, std::string& error);
// Copies a pipe into a temporary file (for readers that scan twice).
bool make_seekable(Input& in, std::string& error);

// What was read: the format detection chose (or the one forced) and, for
// captures, the link type.
struct InputInfo {
  std::string file;
  Format format = Format::automatic;
  std::string link;  // pcap/pcapng: libpcap's name of the link type
};

// The ports of top::known_ports() of one transport.
std::set<std::uint16_t> known_ports(bool tcp);

struct SourceOptions {
  std::set<std::uint16_t> udp_ports = known_ports(false);
  std::set<std::uint16_t> tcp_ports = known_ports(true);
  // Called now and then with (bytes read, total bytes) for a progress bar.
  std::function<void(std::uint64_t, std::uint64_t)> progress;
  // Called once per input when its format (and link type) is known, before
  // its first record.
  std::function<void(const InputInfo&)> on_input;
  // Called with each packet of a pcap/pcapng source before it is dissected:
  // (link type, time, captured bytes, length on the wire, record); read -w.
  std::function<void(int, std::int64_t, std::string_view, std::uint32_t, std::uint64_t)> packet;
};

// Dissects one captured packet of link type `dlt` (Ethernet with VLAN tags,
// Linux SLL/SLL2, raw IP, BSD loopback; IPv4/IPv6; UDP/TCP) and hands any
// TOP payload to the analyzer. Returns false when it is not TOP traffic.
class Dissector {
 public:
  Dissector(Analyzer& a, const SourceOptions& o) : a_(a) {
    for (auto p : o.udp_ports) udp_port_[p] = true;
    for (auto p : o.tcp_ports) tcp_port_[p] = true;
  }
  bool packet(int dlt, std::int64_t ts, const std::uint8_t* data, std::uint32_t caplen,
              std::uint32_t len, std::uint64_t record);
  static bool supported(int dlt);

 private:
  bool ip(std::int64_t ts, const std::uint8_t* p, std::size_t n, std::size_t off,
          std::uint64_t record);
  void bad(std::int64_t ts, std::uint64_t record, std::size_t off, std::string msg);
  Analyzer& a_;
  std::set<std::string> tcp_top_;  // TCP flows recognised by content (bounded)
  Endpoint src_, dst_;             // the endpoints of the packet at hand
  // SourceOptions::udp_ports / tcp_ports as tables: a lookup per packet
  std::vector<bool> udp_port_ = std::vector<bool>(65536), tcp_port_ = std::vector<bool>(65536);
};

// Reads a capture file of any supported format into the analyzer. Returns
// false and sets `error` when the file cannot be read at all (exit 2);
// problems inside the file become findings.
// A damaged capture (damaged_capture()), a --format that the file is not
// and a cut file header are such errors. `info`, when given, says what was
// read.
bool read_file(const std::string& path, Format format, Analyzer& a, const SourceOptions& o,
               std::string& error, InputInfo* info = nullptr);
bool read_input(Input& in, Format format, Analyzer& a, const SourceOptions& o, std::string& error,
                InputInfo* info = nullptr);

// Live capture on an interface with an optional BPF filter until `stop` is
// set (SIGINT). Returns false with `error` (and `permission` when the cause
// is a lack of capture privileges) when the capture cannot start.
bool capture_live(const std::string& iface, const std::string& bpf, Analyzer& a,
                  const SourceOptions& o, const std::atomic<bool>& stop, std::string& error,
                  bool& permission);

// How long a live serial line must be quiet before a frame held to see
// whether CR/LF follows is released (a CR/LF within it belongs to the
// frame; an FTDI adapter's default latency timer is 16 ms).
inline constexpr std::chrono::milliseconds kSerialQuiet{50};

// Reads one serial device (one tap: frames go from the device's name to
// "peer") or two (two taps of one UART, one per direction: one
// conversation, each device named for the direction it taps) at `baud`
// (8N1) until `stop` is set.
bool read_serial_ports(const std::vector<std::string>& devices, unsigned baud, Analyzer& a,
                       const std::atomic<bool>& stop, std::string& error);

// The most bytes read_merged holds to merge two logs.
inline constexpr std::size_t kMaxMergeBytes = std::size_t{256} << 20;

// Two serial logs with times, each one tap (one direction) of one UART,
// merged by time into one conversation: each log's frames go from its name
// to the other's. Captures and raw dumps (no times) are errors.
bool read_merged(const std::vector<std::string>& paths, Format format, Analyzer& a,
                 const SourceOptions& o, std::string& error, std::vector<InputInfo>* infos);

// Current time in microseconds since the epoch.
std::int64_t now_us();

// Parses "2024-05-01T12:00:00.123Z", "...+02:00", or plain epoch seconds
// ("1714564800.5"); microseconds since the epoch.
std::optional<std::int64_t> parse_time(std::string_view s);
// "2024-05-01T12:00:00.123456Z"
std::string format_time(std::int64_t us);

}  // namespace topdump
