// The space-time motion graph: clip sampling, per-sample Delaunay formation edges, features (Eq. 1–7), for
// 50 to 3,000 agents × 300 samples, on 1 and 2 threads (the work is split by sample; results are identical).
//
// Run: bench_graph --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "../../tests/graph/synthetic_crowd.h"

#include <throng/core/parallel.h>
#include <throng/graph/features.h>

#include <benchmark/benchmark.h>

namespace {

using namespace throng;

CrowdMotion crowd_of(int agents) {
  int rows = 5, cols = 10;
  if (agents == 300) rows = 15, cols = 20;
  if (agents == 1000) rows = 25, cols = 40;
  if (agents == 3000) rows = 50, cols = 60;
  return test::marching_grid(rows, cols, 599, 1.0, 1.2, 0.1, 0.1, 0.2);
}

ClipOptions every_second_frame() {
  ClipOptions o;
  o.sample_step = 2;  // 300 samples
  return o;
}

void BM_Formation(benchmark::State& state) {
  const CrowdMotion crowd = crowd_of(static_cast<int>(state.range(0)));
  const Clip clip = make_clip(crowd, every_second_frame());
  ThreadLimit threads(static_cast<std::size_t>(state.range(1)));
  std::size_t edges = 0;
  for (auto _ : state) {
    const MotionGraph g = build_motion_graph(clip, {});
    edges = g.formation_edge_count();
  }
  state.counters["edges"] = static_cast<double>(edges);
  state.counters["samples/s"] = benchmark::Counter(300.0 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Features(benchmark::State& state) {
  const CrowdMotion crowd = crowd_of(static_cast<int>(state.range(0)));
  const MotionGraph g = build_motion_graph(make_clip(crowd, every_second_frame()), {});
  ThreadLimit threads(static_cast<std::size_t>(state.range(1)));
  std::size_t count = 0;
  for (auto _ : state) {
    const FeatureSet f = compute_features(g);
    count = f.spatial.size() + f.temporal.size() + f.spatiotemporal.size();
  }
  state.counters["features"] = static_cast<double>(count);
}

void BM_Clip(benchmark::State& state) {
  const CrowdMotion crowd = crowd_of(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(make_clip(crowd, every_second_frame()).positions.data());
}

void grid(benchmark::internal::Benchmark* b) {
  for (int agents : {50, 300, 1000, 3000})
    for (int threads : {1, 2}) b->Args({agents, threads});
  b->ArgNames({"agents", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

}  // namespace

BENCHMARK(BM_Clip)->Arg(50)->Arg(300)->Arg(1000)->Arg(3000)->ArgName("agents")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Formation)->Apply(grid);
BENCHMARK(BM_Features)->Apply(grid);
