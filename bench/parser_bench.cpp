// Micro-benchmarks of the parser, the stream decoder, the decoder and the
// analyzer's per-datagram path. Items are frames; compare with the figures
// in README.md measured on the same machine.
#include <benchmark/benchmark.h>

#include <string>
#include <type_traits>
#include <vector>

#include "output/output.hpp"
#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"
#include "session/analyzer.hpp"
#include "top/detail/decode_cache.hpp"
#include "top/frame.hpp"
#include "top/top.hpp"

namespace {

const std::string kFrame = top::with_checksum("#tpUG6wGAYEC7832");

void BM_parse_frame(benchmark::State& s) {
  for (auto _ : s) {
    auto r = top::parse_frame(kFrame, true);
    benchmark::DoNotOptimize(r);
  }
  s.SetItemsProcessed(s.iterations());
}
BENCHMARK(BM_parse_frame);

// Into one reused result, as the analyzer's datagram path parses.
void BM_parse_frame_reused(benchmark::State& s) {
  top::ParseResult r;
  for (auto _ : s) {
    top::parse_frame(kFrame, true, top::ParseOptions{}, r);
    benchmark::DoNotOptimize(r);
  }
  s.SetItemsProcessed(s.iterations());
}
BENCHMARK(BM_parse_frame_reused);

void BM_stream_decoder(benchmark::State& s) {
  std::string buf;
  for (int i = 0; i < 1000; ++i) buf += kFrame;
  for (auto _ : s) {
    top::StreamDecoder d;
    d.feed(buf);
    d.finish();
    top::StreamItem it;
    int n = 0;
    while (d.next(it)) ++n;
    benchmark::DoNotOptimize(n);
  }
  s.SetItemsProcessed(s.iterations() * 1000);
}
BENCHMARK(BM_stream_decoder);

void BM_decode(benchmark::State& s) {
  auto r = top::parse_frame(kFrame, true);
  for (auto _ : s) {
    auto d = top::decode(r.frame);
    benchmark::DoNotOptimize(d);
  }
  s.SetItemsProcessed(s.iterations());
}
BENCHMARK(BM_decode);

// The verdict only, into one reused result (topdump stats); with `cache`,
// through a DecodeCache as topdump stats decodes: the frame's shape is known
// after the first iteration, so only its data is judged.
void decode_verdict(benchmark::State& s, top::detail::DecodeCache* cache) {
  auto r = top::parse_frame(kFrame, true);
  top::Decoded d;
  top::DecodeOptions o;
  o.detail = false;
  if (cache != nullptr)
    for (auto _ : s) {
      benchmark::DoNotOptimize(top::detail::decode(r.frame, o, cache, d));
      benchmark::DoNotOptimize(d);
    }
  else
    for (auto _ : s) {
      top::decode(r.frame, o, d);
      benchmark::DoNotOptimize(d);
    }
  s.SetItemsProcessed(s.iterations());
}
void BM_decode_verdict(benchmark::State& s) { decode_verdict(s, nullptr); }
BENCHMARK(BM_decode_verdict);
void BM_decode_verdict_cached(benchmark::State& s) {
  top::detail::DecodeCache cache;
  decode_verdict(s, &cache);
}
BENCHMARK(BM_decode_verdict_cached);

struct Null : topdump::Sink {};
struct Json : topdump::Sink {
  std::string out;
  void frame(const topdump::FrameEvent& e) override {
    topdump::write_frame_json(out, e);
    if (out.size() > (1 << 16)) out.clear();
  }
};

// topdump stats judges without detail; read --json with it.
template <class S>
void analyzer_datagrams(benchmark::State& s) {
  S sink;
  topdump::AnalyzerOptions o;
  o.detail = std::is_same_v<S, Json>;
  topdump::Analyzer a(o, sink);
  topdump::Endpoint c, d;
  c.family = d.family = 4;
  c.port = 40000;
  d.port = 5000;
  d.addr[3] = 1;
  std::string req = kFrame, resp = top::with_checksum("#tpGU6wGAYEC7832");
  std::int64_t t = 1714564800LL * 1000000;
  std::uint64_t rec = 0;
  for (auto _ : s) {
    a.datagram(t, c, d, req, ++rec, 42);
    a.datagram(t + 1000, d, c, resp, ++rec, 42);
    t += 10000;
  }
  s.SetItemsProcessed(s.iterations() * 2);
}
void BM_analyzer_stats(benchmark::State& s) { analyzer_datagrams<Null>(s); }
void BM_analyzer_json(benchmark::State& s) { analyzer_datagrams<Json>(s); }
BENCHMARK(BM_analyzer_stats);
BENCHMARK(BM_analyzer_json);

}  // namespace

BENCHMARK_MAIN();
