// Spectral formation control at scale. Targets on the 2-core machine (issue 6): the 1,260-individual hierarchy
// × 991 frames in ≤ 2 s (BM_ShippedHierarchy1260: the shipped configs/formation-hierarchy-1260.yaml, read as
// `throng formation` reads it); a flat 1,000-individual transition × 1,000 frames in ≤ 10 s
// (BM_FlatTransition/n:1000).
//
//   build/<dir>/bench/formation/bench_formation --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// The cost is dense linear algebra through OpenBLAS (eigen-decompositions, products). OpenBLAS 0.3.21 does not
// know this machine's CPU model and would fall back to its generic kernels, about 3 times slower here; every
// benchmark program's main sets up the process (throng/process/process.h), which switches to the right ones.
#include <throng/formation/formation.h>
#include <throng/io/config.h>
#include <throng/io/formation_job.h>

#include <throng/core/parallel.h>

#include "scenes.h"

#include <benchmark/benchmark.h>

namespace {

using throng::formation::Options;

void run(benchmark::State& state, const throng::formation::Problem& problem, const Options& options) {
  std::size_t frames = 0;
  for (auto _ : state) {
    const auto result = throng::formation::animate_formation(problem, options);
    frames = result.motion.frame_count();
    benchmark::DoNotOptimize(result.motion.positions.data());
  }
  state.counters["individuals"] = static_cast<double>(problem.keyframes[0].positions.rows());
  state.counters["frames"] = static_cast<double>(frames);
}

// Flat transitions (two keyframes, one group) of 60, 250, 1,000 and 2,000 individuals × 1,000 frames; the second
// argument is the thread count (0 = all).
void BM_FlatTransition(benchmark::State& state) {
  const throng::formation::Problem problem = throng::test::flat_transition(static_cast<int>(state.range(0)));
  const throng::ThreadLimit threads(static_cast<std::size_t>(state.range(1)));
  run(state, problem, Options{});
}
BENCHMARK(BM_FlatTransition)
    ->ArgNames({"n", "threads"})
    ->Args({60, 0})
    ->Args({250, 0})
    ->Args({1000, 0})
    ->Args({1000, 1})
    ->Args({2000, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The shipped example of the paper's Figure 11 (configs/formation-hierarchy-1260.yaml): 1,260 = 35 × 6 × 6 in
// three levels, a circle, a star, a runner and five circles, 991 frames; the job is read once, outside the loop.
void BM_ShippedHierarchy1260(benchmark::State& state) {
  const throng::FormationJob job =
      throng::read_job<throng::FormationJob>(throng::ConfigNode::load_file(THRONG_CONFIG_DIR "/formation-hierarchy-1260.yaml"));
  const throng::ThreadLimit threads(static_cast<std::size_t>(state.range(0)));
  run(state, job.problem, job.options);
}
BENCHMARK(BM_ShippedHierarchy1260)->ArgName("threads")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The tests' version of the same crowd (tests/formation/scenes.cpp paper_crowd(): the same sizes and figures,
// each group a turning ring assigned to the nearest place of the next figure), which the collision and flat
// variants below use: the same work as the shipped config to within the layout's effect on the rotations.
void BM_PaperCrowdHierarchy(benchmark::State& state) {
  const throng::formation::Problem problem = throng::test::paper_crowd();
  const throng::ThreadLimit threads(static_cast<std::size_t>(state.range(0)));
  run(state, problem, Options{});
}
BENCHMARK(BM_PaperCrowdHierarchy)->ArgName("threads")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same crowd flat (one group of 1,260 over four keyframes): what the hierarchy saves.
void BM_PaperCrowdFlat(benchmark::State& state) {
  throng::formation::Problem problem = throng::test::paper_crowd();
  problem.hierarchy.reset();
  run(state, problem, Options{});
}
BENCHMARK(BM_PaperCrowdFlat)->Unit(benchmark::kMillisecond)->UseRealTime();

// The hierarchy with collision avoidance (§4.3) at 0.6 m: the spectral paths of these four figures cross a lot.
void BM_PaperCrowdCollisions(benchmark::State& state) {
  const throng::formation::Problem problem = throng::test::paper_crowd();
  Options options;
  options.collision.enabled = true;
  options.collision.min_distance_m = 0.6;
  run(state, problem, options);
}
BENCHMARK(BM_PaperCrowdCollisions)->Unit(benchmark::kMillisecond)->UseRealTime();

// Automatic hierarchy (spectral clustering, groups of ≤ 8) on the 1,260 crowd without its tree.
void BM_PaperCrowdAutoHierarchy(benchmark::State& state) {
  throng::formation::Problem problem = throng::test::paper_crowd();
  problem.hierarchy.reset();
  Options options;
  options.auto_group_size = 8;
  run(state, problem, options);
}
BENCHMARK(BM_PaperCrowdAutoHierarchy)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
