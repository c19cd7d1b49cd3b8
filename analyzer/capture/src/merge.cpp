// Two serial logs, one tap of a UART each, merged by time into one
// conversation.
#include <string>
#include <vector>

#include "capture/read.hpp"
#include "log_reader.hpp"
#include "readers.hpp"

namespace topdump {

namespace {

// Holds the chunks of one log for merging; source notes go through.
class Collector : public CaptureSink {
 public:
  struct Chunk {
    std::int64_t ts;
    std::uint64_t record, offset;
    std::string bytes;
  };
  explicit Collector(CaptureSink& a) : a_(a) {}
  void record(bool) override {}
  void datagram(std::int64_t, const Endpoint&, const Endpoint&, std::string_view, std::uint64_t,
                std::uint32_t) override {}
  void segment(std::int64_t, const Endpoint&, const Endpoint&, std::uint32_t, bool,
               std::string_view, std::uint64_t, std::uint32_t) override {}
  void source_note(std::int64_t ts, ACode code, std::string message, std::uint64_t record,
                   std::uint64_t offset) override {
    a_.source_note(ts, code, std::move(message), record, offset);
  }
  void chunk(std::int64_t ts, Transport, const Endpoint&, const Endpoint&, std::string_view bytes,
             std::uint64_t record, std::uint64_t offset) override {
    if (ts == kNoTime) untimed = true;
    held += bytes.size() + sizeof(Chunk);
    chunks.push_back(Chunk{ts, record, offset, std::string(bytes)});
  }
  std::vector<Chunk> chunks;
  std::size_t held = 0;
  bool untimed = false;

 private:
  CaptureSink& a_;
};

}  // namespace

bool read_merged(const std::vector<std::string>& paths, Format format, CaptureSink& a,
                 const SourceOptions& o, std::string& error, std::vector<InputInfo>* infos) {
  if (paths.size() != 2) {
    error = "two inputs are merged, not " + std::to_string(paths.size());
    return false;
  }
  std::vector<Collector> logs;
  std::vector<std::string> names;
  std::size_t held = 0;
  for (const std::string& p : paths) {
    Input in;
    if (!open_input(p, in, error)) return false;
    Format f = format;
    if (f == Format::automatic) {
      if (auto why = damaged_capture(in.head)) {
        error = in.name + ": " + *why;
        return false;
      }
      f = detect_format(in.head);
    }
    if (f == Format::pcap || f == Format::pcapng || f == Format::raw) {
      error = in.name + ": a " + std::string(to_string(f)) +
              " input cannot be merged: two inputs are two serial taps, each a log with times "
              "(socat, saleae, lines)";
      return false;
    }
    if (infos) infos->push_back(InputInfo{in.name, f, {}});
    if (o.on_input) o.on_input(InputInfo{in.name, f, {}});
    names.push_back(in.name);
    logs.emplace_back(a);
    if (!read_serial_log(in, f, logs.back(), error)) return false;
    held += logs.back().held;
    if (logs.back().untimed) {
      error = in.name + ": a chunk without a time: two taps are merged by time";
      return false;
    }
    if (held > kMaxMergeBytes) {
      error = in.name + ": the two logs hold more than " + std::to_string(kMaxMergeBytes >> 20) +
              " MiB; merge them with fewer bytes";
      return false;
    }
  }
  // each log is one tap, one direction: merged by time, the first log first
  // on equal times
  const Endpoint e0 = named(names[0]), e1 = named(names[1]);
  a.both_ways();  // the two taps are the two directions
  std::size_t i = 0, j = 0;
  const auto& x = logs[0].chunks;
  const auto& y = logs[1].chunks;
  while (i < x.size() || j < y.size()) {
    const bool first = j == y.size() || (i < x.size() && x[i].ts <= y[j].ts);
    const Collector::Chunk& c = first ? x[i++] : y[j++];
    a.record(true);
    a.chunk(c.ts, Transport::serial, first ? e0 : e1, first ? e1 : e0, c.bytes, c.record, c.offset);
  }
  return true;
}

}  // namespace topdump
