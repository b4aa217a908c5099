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

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {

using namespace throng;

// 25 rows × 40 walkers 1 m apart walking +x at 1.4 m/s for 600 frames of 0.1 s; the deformed copy bulges 3 m
// sideways between x = 20 and 60 m (the same scene as tests/timewarp, larger).
struct Scene {
  CrowdMotion original, deformed;
};

const Scene& scene() {
  static const Scene s = [] {
    const std::size_t frames = 600;
    const int rows = 25, cols = 40;
    CrowdMotion c = CrowdMotion::with_shape(frames, static_cast<std::size_t>(rows * cols));
    for (std::size_t f = 0; f < frames; ++f) {
      c.times[f] = 0.1 * static_cast<double>(f);
      for (int r = 0; r < rows; ++r) {
        for (int k = 0; k < cols; ++k) c.position(f, static_cast<std::size_t>(r * cols + k)) << 1.4 * c.times[f] - r, k - 0.5 * (cols - 1), 0.0;
      }
    }
    CrowdMotion d = c;
    for (std::size_t f = 0; f < frames; ++f) {
      for (std::size_t a = 0; a < d.agent_count(); ++a) {
        auto p = d.position(f, a);
        if (p.x() > 20 && p.x() < 60) p.y() += 3.0 * std::sin(std::numbers::pi * (p.x() - 20) / 40);
      }
    }
    return Scene{std::move(c), std::move(d)};
  }();
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
