// topconf fuzz's rate over UDP loopback against a healthy topsim (a Server
// on its own thread), with probes every 10 cases, against a floor measured
// in the same run: one probe exchange (send, wait for the answer) over the
// same socket pair. bench/README.md, section "topconf fuzz", has the figures.
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>
#include <thread>

#include "conf/fuzz.hpp"
#include "sim/server.hpp"

namespace {

topconf::Matrix c12_matrix() {
  const std::string path = std::string(TOPKIT_SOURCE_DIR) + "/conformance/matrices/c12.json";
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  auto r = topconf::load_matrix(ss.str(), path);
  if (!r.matrix) throw std::runtime_error(path + ": cannot load");
  return *r.matrix;
}

struct Sim {
  Sim()
      : server([] {
          topsim::ServerConfig c;
          c.model = top::Model::c12;
          return c;
        }()) {
    thread = std::thread([this] { server.run(); });
  }
  ~Sim() {
    server.stop();
    thread.join();
  }
  topsim::Server server;
  std::thread thread;
};

// The floor: one exchange of the probe, as the fuzzer sends it.
void BM_ProbeExchangeFloor(benchmark::State& state) {
  Sim sim;
  auto t = topconf::open_transport("udp://127.0.0.1:" + std::to_string(sim.server.port()),
                                   top::Model::c12);
  const std::string probe = top::with_checksum("#TPUD2rAWB00");
  std::string out;
  for (auto _ : state) {
    t->send(probe);
    if (!t->receive(t->now_us() + 500000, out)) state.SkipWithError("no answer");
  }
  state.counters["exchanges_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ProbeExchangeFloor)->UseRealTime()->Unit(benchmark::kMicrosecond);

void BM_FuzzUdpProbeEvery10(benchmark::State& state) {
  Sim sim;
  const topconf::Matrix m = c12_matrix();
  auto t = topconf::open_transport("udp://127.0.0.1:" + std::to_string(sim.server.port()),
                                   top::Model::c12);
  const auto n = static_cast<std::uint64_t>(state.range(0));
  std::uint64_t cases = 0, failures = 0, start = 0;
  for (auto _ : state) {
    topconf::FuzzOptions o;
    o.start = start;
    o.end = start + n;
    o.probe_every = 10;
    const auto r = topconf::run_fuzz(m, *t, o);
    cases += r.cases_run;
    failures += r.failures.size();
    start += n;
  }
  state.counters["cases_per_s"] =
      benchmark::Counter(static_cast<double>(cases), benchmark::Counter::kIsRate);
  state.counters["failures"] = static_cast<double>(failures);
}
BENCHMARK(BM_FuzzUdpProbeEvery10)
    ->Arg(10000)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
