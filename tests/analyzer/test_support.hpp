// Helpers shared by the topdump tests.
#pragma once

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "capture/sources.hpp"
#include "json_reference.hpp"
#include "output/output.hpp"
#include "session/analyzer.hpp"

namespace topdump::test {

inline std::string topdump_bin() { return std::string(TOPKIT_BINARY_DIR) + "/analyzer/topdump"; }
inline std::string captures_dir() { return std::string(TOPKIT_SOURCE_DIR) + "/captures"; }

inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// A temporary directory removed at the end of the test.
struct TempDir {
  std::string path;
  TempDir() {
    char t[] = "/tmp/topdump_test_XXXXXX";
    path = mkdtemp(t);
  }
  ~TempDir() { std::system(("rm -rf '" + path + "'").c_str()); }
  std::string file(const std::string& n) const { return path + "/" + n; }
};

// Runs a shell command; stdout into `out`, returns the exit status.
inline int run(const std::string& cmd, std::string& out) {
  out.clear();
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  int st = pclose(p);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// Reads what is available from fd for up to `ms`, until `want` appears.
inline bool read_until(int fd, std::string& acc, const std::string& want, int ms) {
  auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  while (acc.find(want) == std::string::npos) {
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                    end - std::chrono::steady_clock::now())
                    .count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left)) <= 0) continue;
    char buf[4096];
    ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) return acc.find(want) != std::string::npos;
    acc.append(buf, static_cast<std::size_t>(n));
  }
  return true;
}

// Writes a capture of `frames` frames with the bench generator
// (bench/gen_capture.cpp) into `tmp`; its path, or "" when the generator
// failed.
inline std::string generated_capture(const TempDir& tmp, const std::string& name, int frames,
                                     int seed, const std::string& mode = "udp") {
  std::string out;
  const std::string path = tmp.file(name);
  const int rc =
      run("'" + std::string(TOPKIT_BINARY_DIR) + "/analyzer/gen_capture' " +
              std::to_string(frames) + " '" + path + "' " + std::to_string(seed) + " " + mode,
          out);
  return rc == 0 ? path : std::string();
}

// Records every event an analyzer emits.
struct Recorder : Sink {
  struct F {
    std::uint64_t n;
    std::int64_t ts;
    Position pos;
    std::string from, to, raw, ident;
    top::Role role;
    top::Dialect dialect;
    std::uint64_t reply_to;
    std::int64_t latency;
    std::uint64_t copy_of;
    char control;
    std::vector<std::string> codes;  // frame, catalog and session codes
    std::string json_fast;
    std::string json_ref;
  };
  std::vector<F> frames;
  std::vector<NoteEvent> notes;
  std::vector<std::string> garbage_codes;
  std::vector<Position> garbage_pos;
  void frame(const FrameEvent& e) override {
    F f;
    f.n = e.n;
    f.ts = e.ts;
    f.pos = e.pos;
    f.from = *e.from;
    f.to = *e.to;
    f.raw = e.entry->frame->raw;
    f.ident = std::string(e.entry->frame->ident_view());
    f.role = e.entry->decoded.role;
    f.dialect = e.entry->decoded.dialect;
    f.reply_to = e.reply_to;
    f.latency = e.latency_us;
    f.copy_of = e.copy_of;
    f.control = e.entry->frame->control;
    for (const top::Finding* x : all_findings(*e.entry->frame, e.entry->decoded))
      f.codes.emplace_back(top::to_string(x->code));
    for (const Note& n : e.notes) f.codes.emplace_back(to_string(n.code));
    write_frame_json(f.json_fast, e);
    f.json_ref = reference::frame_event_json(e).dump();
    frames.push_back(std::move(f));
  }
  // the JSON of each garbage event, the writer's and nlohmann's dump()
  std::vector<std::pair<std::string, std::string>> garbage_json;
  void garbage(const GarbageEvent& e) override {
    garbage_codes.emplace_back(top::to_string(e.item->finding.code));
    garbage_pos.push_back(e.pos);
    std::string line;
    write_garbage_json(line, e);
    garbage_json.emplace_back(std::move(line), reference::garbage_event_json(e).dump() + "\n");
  }
  // the JSON of each note, fast writer and reference, written while its
  // endpoint strings live (the conversation may be gone after finish())
  std::vector<std::pair<std::string, std::string>> note_json;
  void note(const NoteEvent& e) override {
    notes.push_back(e);
    std::string fast;
    write_note_json(fast, e);
    note_json.emplace_back(std::move(fast), reference::note_event_json(e).dump());
  }
  bool has_note(ACode c) const {
    for (const auto& n : notes)
      if (n.note.code == c) return true;
    return false;
  }
  std::size_t count_note(ACode c) const {
    std::size_t k = 0;
    for (const auto& n : notes) k += n.note.code == c;
    return k;
  }
};

inline bool has_code(const Recorder::F& f, const std::string& c) {
  for (const auto& x : f.codes)
    if (x == c) return true;
  return false;
}

// An IPv4 endpoint 10.0.0.last:port.
inline Endpoint ep4(std::uint8_t last, std::uint16_t port) {
  Endpoint e;
  e.family = 4;
  e.addr[0] = 10;
  e.addr[3] = last;
  e.port = port;
  return e;
}

inline constexpr std::int64_t T = 1714564800LL * 1000000;

// A finished session's pairing counts: requests, paired, unanswered and
// unsolicited, checked as one.
using Counts = std::array<std::uint64_t, 4>;
inline Counts pairing_counts(const Stats& s) {
  return {s.requests, s.paired, s.unanswered, s.unsolicited};
}

// The options of a session whose requests are unanswered after 100 ms, for
// `model` (unknown: any).
inline AnalyzerOptions unanswered_after_100ms(top::Model model = top::Model::unknown) {
  AnalyzerOptions o;
  o.timeout_us = 100000;
  o.model = model;
  return o;
}

struct Fixture {
  Recorder rec;
  AnalyzerOptions opts;
  std::unique_ptr<Analyzer> a;
  Endpoint client = ep4(1, 40000), device = ep4(2, 5000);
  std::uint64_t record = 0;
  Fixture() { a = std::make_unique<Analyzer>(opts, rec); }
  void reset(AnalyzerOptions o) {
    opts = o;
    a = std::make_unique<Analyzer>(opts, rec);
  }
  void up(std::int64_t ms, const std::string& p) {
    a->datagram(T + ms * 1000, client, device, p, ++record, 42);
  }
  void down(std::int64_t ms, const std::string& p) {
    a->datagram(T + ms * 1000, device, client, p, ++record, 42);
  }
  // `request` (checksum appended) at `ms`, echoed with the addresses swapped
  // `after` ms later.
  void echoed(std::int64_t ms, std::int64_t after, std::string request) {
    up(ms, top::with_checksum(request));
    std::swap(request[3], request[4]);
    down(ms + after, top::with_checksum(request));
  }
};

// Reads a capture file through an Analyzer into a Recorder.
inline Recorder read(const std::string& path, SourceOptions o = {}, Format f = Format::automatic) {
  Recorder r;
  Analyzer a(AnalyzerOptions{}, r);
  std::string err;
  EXPECT_TRUE(read_file(path, f, a, o, err)) << err;
  a.finish();
  return r;
}

}  // namespace topdump::test
