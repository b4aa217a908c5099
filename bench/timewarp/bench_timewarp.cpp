// The time warp at scale (issue 4): 1,000 agents × 600 frames whose paths bulge sideways (so they walk faster
// there), warped back towards the original speeds: the whole method, the warp alone (closed form and smoothed)
// and the spline resampling alone. Counter peak_heap_MB: the largest heap in use during the warp above what was
// in use before (bench/common/heap.h; the output crowd is part of it).
//
// Run:   bench_timewarp --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <throng/timewarp/resample.h>
#include <throng/timewarp/timewarp.h>

#include <benchmark/benchmark.h>

#include "../common/heap.h"
#include "bulge_scene.h"

#include <algorithm>

namespace {

using namespace throng;

// bench::bulge_scene (bulge_scene.h): 25 rows × 40 walkers × 600 frames, the deformed copy bulging sideways.
const bench::BulgeScene& scene() {
  static const bench::BulgeScene s = bench::bulge_scene(25, 40, 600);
  return s;
}

void time_warp_1000x600(benchmark::State& state) {
  timewarp::Options o;
  o.smoothing_time = static_cast<double>(state.range(0));
  (void)scene();  // built before the memory reading
  timewarp::Report report;
  double peak_mb = 0;
  for (auto _ : state) {
    bench::HeapPeak peak;
    const timewarp::Result r = timewarp::time_warp(scene().deformed, scene().original, o);
    peak_mb = std::max(peak_mb, peak.stop());
    report = r.report;
    benchmark::DoNotOptimize(r.crowd.positions.data());
  }
  state.counters["peak_heap_MB"] = peak_mb;
  state.counters["frames_out"] = static_cast<double>(report.frames_out);
  state.counters["deviation_before"] = report.speed_deviation_before;
  state.counters["deviation_after"] = report.speed_deviation_after;
}
BENCHMARK(time_warp_1000x600)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void solve_warp_1000x600(benchmark::State& state) {
  timewarp::Options o;
  o.smoothing_time = static_cast<double>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(timewarp::solve_warp(scene().deformed, scene().original, o).warped_times.back());
}
BENCHMARK(solve_warp_1000x600)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void resample_1000x600(benchmark::State& state) {
  const CrowdMotion& c = scene().deformed;
  const std::vector<double> times = timewarp::uniform_times(c.times.front(), c.times.back(), 24.0);
  for (auto _ : state) benchmark::DoNotOptimize(timewarp::resample_crowd(c, c.times, times).positions.data());
  state.counters["frames_out"] = static_cast<double>(times.size());
}
BENCHMARK(resample_1000x600)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
