// The independent motion checker (throng check-motion's measures, solver/check) against the crowd's size: every
// agent's kinematics, their distributions and the contacts, on N agents × 601 frames of the tests' marching grid
// (10 frames per second, 1 m apart, 1.2 m/s along a gentle arc), 2 threads; `heap_mb`: the most heap the call
// held beyond the crowd. Before 6 December 2026 (a sort per percentile set, an agent and a time kept with every
// sample, merged samples grown by appends, no y test in the contact sweep): 1,000 agents 214 ms, 10,000 agents
// 3.99 s and 1.96 GB; now 63-68 ms, 1.10-1.13 s and 0.44 GB (docs/commands/check-motion.md).
//
// Run: build/<dir>/bench/check/bench_check --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include "../../tests/graph/synthetic_crowd.h"
#include "../common/heap.h"

#include <throng/check/motion_check.h>
#include <throng/core/parallel.h>

#include <benchmark/benchmark.h>

namespace {

using namespace throng;

void BM_Measure(benchmark::State& state) {
  const int agents = static_cast<int>(state.range(0));
  const CrowdMotion crowd = test::marching_grid(agents / 100, 100, 601, 1.0, 1.2, 0.1, 0.02, 0.1);
  const ThreadLimit threads(2);
  double held = 0;
  for (auto _ : state) {
    bench::HeapPeak peak;
    const check::Statistics s = check::measure(crowd, {}, check::Settings{});
    benchmark::DoNotOptimize(s.speed.p99);
    held = std::max(held, peak.stop());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(crowd.agent_count() * crowd.frame_count()));
  state.counters["heap_mb"] = held;
}
BENCHMARK(BM_Measure)->ArgName("agents")->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
