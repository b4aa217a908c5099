// Spectral formation control at scale. Targets on the 2-core machine (issue 6): the 1,260-individual hierarchy
// × 991 frames in ≤ 2 s (BM_ShippedHierarchy1260: the shipped configs/formation-hierarchy-1260.yaml, read as
// `throng formation` reads it); a flat 1,000-individual transition × 1,000 frames in ≤ 10 s
// (BM_FlatTransition/n:1000). Issue 19: 10,000 individuals × 1,000 frames in ≤ 5 s (BM_Crowd/n:10000, the
// automatic hierarchy), with time and peak heap against n and their growth exponents (printed after the runs).
//
//   build/<dir>/bench/formation/bench_formation --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//   build/<dir>/bench/formation/bench_formation --benchmark_filter=BM_Crowd --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true       (one line: the scaling table and its growth exponents)
//
// The output goes through a console reporter that adds the growth lines (growth_reporter.h); the CPU column of
// the BM_Crowd families is the whole process's CPU time (all threads), which stays meaningful on a shared
// machine where the wall time does not.
//
// The cost is dense linear algebra through OpenBLAS (eigen-decompositions, products). OpenBLAS 0.3.21 does not
// know this machine's CPU model and would fall back to its generic kernels, about 3 times slower here; every
// benchmark program's main sets up the process (throng/process/process.h), which switches to the right ones.
#include <throng/process/huge_pages.h>
#include <throng/formation/formation.h>
#include <throng/io/config.h>
#include <throng/io/formation_job.h>

#include <throng/core/parallel.h>

#include "../common/heap.h"
#include "../common/growth_reporter.h"
#include "scenes.h"

#include <benchmark/benchmark.h>

#include <algorithm>

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

// Largest speed of any individual between consecutive frames (m/s): the benchmarked output stays plausible.
double largest_speed(const throng::CrowdMotion& m) {
  double fastest = 0.0;
  for (std::size_t f = 1; f < m.frame_count(); ++f)
    fastest = std::max(fastest, (m.frame(f) - m.frame(f - 1)).rowwise().norm().maxCoeff() / (m.times[f] - m.times[f - 1]));
  return fastest;
}

// Default options (flat up to Options::auto_group_size = 2,000 individuals, an automatic hierarchy of groups of
// at most Options::auto_cluster_size = 250 items beyond), all threads; peak heap of the call including its
// output (#frames × n × 3 doubles: 240 MB at 10,000).
void run_scaling(benchmark::State& state, const throng::formation::Problem& problem, const Options& options) {
  const throng::ThreadLimit threads(0);
  double peak = 0.0, fastest = 0.0;
  std::size_t frames = 0, groups = 0;
  for (auto _ : state) {
    throng::bench::HeapPeak heap;
    const auto result = throng::formation::animate_formation(problem, options);
    peak = std::max(peak, heap.stop());
    state.PauseTiming();
    frames = result.motion.frame_count();
    groups = result.hierarchy.subgroups.size();
    fastest = largest_speed(result.motion);
    state.ResumeTiming();
  }
  const auto n = problem.keyframes[0].positions.rows();
  state.counters["individuals"] = static_cast<double>(n);
  state.counters["frames"] = static_cast<double>(frames);
  state.counters["top_groups"] = static_cast<double>(groups);
  state.counters["regime"] = n > options.auto_group_size ? 1.0 : 0.0;
  state.counters["peak_heap_mb"] = peak;
  state.counters["max_speed_m_per_s"] = fastest;
}

// A crowd that keeps its neighbours (tests/formation/scenes.h marching_crowd: 20 m march, a 20° turn and a
// stretch, the fastest individual at 1 m/s on a straight line), 1,000 frames: the time and memory against n of issue 19.
void BM_Crowd(benchmark::State& state) {
  Options options;
  const throng::formation::Problem problem = throng::test::marching_crowd(static_cast<int>(state.range(0)), options.frame_rate_hz);
  run_scaling(state, problem, options);
}
BENCHMARK(BM_Crowd)
    ->ArgName("n")
    ->Arg(1000)
    ->Arg(2000)
    ->Arg(5000)
    ->Arg(10000)
    ->Arg(20000)
    ->Arg(50000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

// The same sizes on the flat transition's scene (every individual crosses to an unrelated place, 1,000 frames):
// the graphs summed over the keyframes have no small separator, so the clustering takes its other path (plain
// Lanczos, solver/formation/src/fiedler.h). Its speeds are not a walk's beyond a few hundred individuals: a
// measure of the clustering, not a plausible crowd.
void BM_CrowdReshuffled(benchmark::State& state) {
  run_scaling(state, throng::test::flat_transition(static_cast<int>(state.range(0))), Options{});
}
BENCHMARK(BM_CrowdReshuffled)
    ->ArgName("n")
    ->Arg(5000)
    ->Arg(10000)
    ->Arg(20000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

}  // namespace

int main(int argc, char** argv) {
  throng::restart_with_huge_pages(argv);  // as the program does (throng/process/huge_pages.h)
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  throng::bench::GrowthReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
