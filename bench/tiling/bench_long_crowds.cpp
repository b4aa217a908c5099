// Long repeating crowds (issue 15): a 40 m × 40 m plaza tiled for one hour at 0.05 characters/m² in windows of
// 60 s, and the 10 m × 10 m × 20 s tile periodic in x, y and t for twenty seeds.
//
// Targets: the hour perfect across every seam (BM_PlazaHourChecked: the independent checker on the whole delivered
// tiling; BM_PlazaHour: no dangling end lost), the density held in every minute within 10 % (density_worst: the
// largest |mean − target| / target over the 60 minutes), peak heap within 1.5 × that of a single 60 s window
// (heap_ratio), wall time ≤ 5 min on this 2-core machine, and the time per window constant along the hour
// (window_first10_s, window_middle10_s, window_last10_s: mean seconds of windows 1–10, 25–34 and 50–59; slope_ms:
// the least-squares change of a window's time per window index). The loop: 20 perfect of 20 (perfect), with the
// median and largest time per seed. BM_PlazaHourStreamed: the same hour written to a crowd file window by window,
// as `throng tile configs/tile-plaza-hour.yaml` writes it.
//
// Run: build/<dir>/bench/tiling/bench_tiling --benchmark_filter='Plaza|Loop' --benchmark_repetitions=3
//      --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <throng/core/parallel.h>
#include <throng/core/progress.h>
#include <throng/io/tiling_stream.h>
#include <throng/tiling/check.h>
#include <throng/tiling/density.h>
#include <throng/tiling/library.h>
#include <throng/tiling/tile.h>
#include <throng/tiling/windowed.h>

#include "../common/heap.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

using namespace throng;
using namespace throng::tiling;

namespace {

PatchLibrary plaza_library() {
  return builtin_library({"walk", "walk_slow", "walk_fast", "turn_left", "turn_right", "turn_left_90", "turn_right_90",
                          "stop", "start", "wait", "turn_in_place", "meet", "pass", "handshake", "bump"});
}

Environment plaza(double seconds) {
  Environment e;
  e.scene.region = Region{{0, 0}, {40, 40}, 0, seconds, {false, false, false}};
  return e;
}

Options plaza_options() {
  Options o;
  o.seed = 1;
  o.chains = 2;
  o.annealing.max_failures = 2000;
  o.density.per_m2 = 0.05;
  return o;
}

// What a windowed run measures: the seconds of each window, the density of each minute, a digest of everything
// delivered (the same bits in every run), and the dangling ends lost.
struct Hour {
  std::vector<double> window_seconds;
  double density_worst = 0;
  std::uint64_t digest = 1469598103934665603ull;
  std::size_t lost = 0;
  std::size_t instances = 0;
  std::size_t agents = 0;

  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) digest = (digest ^ p[i]) * 1099511628211ull;
  }
  void take(const WindowOutput& out) {
    window_seconds.push_back(out.report.seconds);
    lost = out.lost_dangling;
    instances += out.instances.size();
    for (const Instance& i : out.instances) {
      for (const Path& p : i.paths) add(p.times.data(), p.times.size() * sizeof(double));
    }
    for (const FrameWindow& f : out.frames) {
      for (const AreaDensity& a : f.density.areas) density_worst = std::max(density_worst, std::abs(a.error()));
      add(f.frames.positions.data(), f.frames.positions.size() * sizeof(double));
      if (!f.frames.ids.empty()) agents = std::max<std::size_t>(agents, static_cast<std::size_t>(f.frames.ids.back()) + 1);
    }
  }
};

// Runs a windowed plaza of `seconds`, calling `keep` with each output.
template <class Keep>
Hour run_plaza(double seconds, Keep&& keep) {
  const PatchLibrary lib = plaza_library();
  const Environment env = plaza(seconds);
  WindowedTiler tiler(lib, env, plaza_options(), WindowOptions{60, 10});
  Hour hour;
  NoProgress quiet;
  tile_windows(tiler, [&](const WindowOutput& out, const WindowedTiler&) {
    hour.take(out);
    keep(out);
  }, quiet);
  return hour;
}

std::uint64_t hour_digest = 0;  // BM_PlazaHour's, for BM_PlazaHourChecked to compare

double mean(const std::vector<double>& v, std::size_t from, std::size_t to) {
  to = std::min(to, v.size());
  double s = 0;
  for (std::size_t i = from; i < to; ++i) s += v[i];
  return to > from ? s / static_cast<double>(to - from) : 0.0;
}

// The hour with no output kept: time, peak heap, density, lost ends; and the peak heap of a single 60 s window
// (a plaza of 60 s: one window, tiled and delivered) for the ratio.
void BM_PlazaHour(benchmark::State& state) {
  const ThreadLimit limit(2);
  Hour hour;
  double window_peak = 0, hour_peak = 0;
  for (auto _ : state) {
    state.PauseTiming();
    {
      bench::HeapPeak peak;
      (void)run_plaza(60, [](const WindowOutput&) {});
      window_peak = peak.stop();
    }
    state.ResumeTiming();
    bench::HeapPeak peak;
    hour = run_plaza(3600, [](const WindowOutput&) {});
    hour_peak = peak.stop();
  }
  hour_digest = hour.digest;
  const std::vector<double>& w = hour.window_seconds;
  // Least-squares slope of the window time over the window index (windows 1 .. 58: the first has no carried
  // instances, the last no look-ahead).
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (std::size_t i = 1; i + 1 < w.size(); ++i) {
    const auto x = static_cast<double>(i);
    sx += x;
    sy += w[i];
    sxx += x * x;
    sxy += x * w[i];
    n += 1;
  }
  state.counters["windows"] = static_cast<double>(w.size());
  state.counters["instances"] = static_cast<double>(hour.instances);
  state.counters["agents"] = static_cast<double>(hour.agents);
  state.counters["lost_dangling"] = static_cast<double>(hour.lost);
  state.counters["density_worst"] = hour.density_worst;
  state.counters["window_first10_s"] = mean(w, 1, 11);
  state.counters["window_middle10_s"] = mean(w, 25, 35);
  state.counters["window_last10_s"] = mean(w, 50, 60);
  state.counters["slope_ms"] = n > 1 ? 1000 * (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
  state.counters["window_heap_mb"] = window_peak;
  state.counters["hour_heap_mb"] = hour_peak;
  state.counters["heap_ratio"] = window_peak > 0 ? hour_peak / window_peak : 0.0;
  state.counters["max_rss_mb"] = bench::max_rss_mb();
  if (hour.lost != 0) state.SkipWithError("dangling ends were lost: the hour is not perfect");
  if (hour.density_worst > 0.1) state.SkipWithError("a minute's density is more than 10 % off its target");
}
BENCHMARK(BM_PlazaHour)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// The same hour, its whole delivered tiling kept and proven perfect by the independent checker (check_seconds),
// with the digest of BM_PlazaHour's run (same_bits: 1 when that ran first and matched).
void BM_PlazaHourChecked(benchmark::State& state) {
  const ThreadLimit limit(2);
  Tiling whole;
  Hour hour;
  CheckReport report;
  double check_seconds = 0;
  for (auto _ : state) {
    whole = Tiling{};
    hour = run_plaza(3600, [&](const WindowOutput& out) {
      whole.instances.insert(whole.instances.end(), out.instances.begin(), out.instances.end());
      whole.connections.insert(whole.connections.end(), out.connections.begin(), out.connections.end());
    });
    const auto started = std::chrono::steady_clock::now();
    const Options o = plaza_options();
    CheckOptions c;
    c.limits = o.limits;
    c.match = o.match;
    report = check_tiling(plaza_library(), whole, plaza(3600), c);
    check_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
  state.counters["instances"] = static_cast<double>(whole.instances.size());
  state.counters["connections"] = static_cast<double>(whole.connections.size());
  state.counters["failures"] = static_cast<double>(report.total());
  state.counters["check_s"] = check_seconds;
  state.counters["same_bits"] = hour_digest == 0 ? -1.0 : (hour_digest == hour.digest ? 1.0 : 0.0);
  if (!report.perfect()) state.SkipWithError("the checker found failures in the delivered hour");
  if (hour_digest != 0 && hour_digest != hour.digest) state.SkipWithError("not the same bits as BM_PlazaHour");
}
BENCHMARK(BM_PlazaHourChecked)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// The hour as `throng tile configs/tile-plaza-hour.yaml` makes it: every window streamed to a crowd file (slots,
// tiling rows, flushed per window; io/tiling_stream.h) as it is delivered. Wall time (the command's target, ≤ 5 min),
// the file's size, and the peak heap against that of a streamed 60 s plaza (heap_ratio ≤ 1.5); the mean seconds per
// window at the start, middle and end of the hour (constant: linear in duration).
double stream_plaza(double seconds, const std::filesystem::path& path, std::vector<double>* window_seconds) {
  const PatchLibrary lib = plaza_library();
  const Environment env = plaza(seconds);
  WindowedTiler tiler(lib, env, plaza_options(), WindowOptions{60, 10});
  TilingStreamSetup setup;
  setup.library = &lib;
  setup.environment = &env;
  setup.check.limits = plaza_options().limits;
  setup.check.match = plaza_options().match;
  TilingStreamWriter writer(path, path.filename().string(), setup);
  NoProgress quiet;
  const std::size_t lost = tile_windows(tiler, [&](const WindowOutput& out, const WindowedTiler&) {
    const auto started = std::chrono::steady_clock::now();
    writer.append(out);
    if (window_seconds) {
      window_seconds->push_back(out.report.seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    }
  }, quiet);
  WindowedSummary summary;
  summary.record = writer.record();
  writer.finish(summary);
  return static_cast<double>(lost);
}

void BM_PlazaHourStreamed(benchmark::State& state) {
  const ThreadLimit limit(2);
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::filesystem::path hour_file = dir / "throng-bench-hour.h5", window_file = dir / "throng-bench-window.h5";
  std::vector<double> w;
  double window_peak = 0, hour_peak = 0, lost = 0;
  for (auto _ : state) {
    state.PauseTiming();
    {
      bench::HeapPeak peak;
      (void)stream_plaza(60, window_file, nullptr);
      window_peak = peak.stop();
    }
    w.clear();
    state.ResumeTiming();
    bench::HeapPeak peak;
    lost = stream_plaza(3600, hour_file, &w);
    hour_peak = peak.stop();
  }
  state.counters["windows"] = static_cast<double>(w.size());
  state.counters["lost_dangling"] = lost;
  state.counters["file_mb"] = static_cast<double>(std::filesystem::file_size(hour_file)) / (1024.0 * 1024.0);
  state.counters["window_first10_s"] = mean(w, 1, 11);
  state.counters["window_middle10_s"] = mean(w, 25, 35);
  state.counters["window_last10_s"] = mean(w, 50, 60);
  state.counters["window_heap_mb"] = window_peak;
  state.counters["hour_heap_mb"] = hour_peak;
  state.counters["heap_ratio"] = window_peak > 0 ? hour_peak / window_peak : 0.0;
  std::filesystem::remove(hour_file);
  std::filesystem::remove(window_file);
  if (lost != 0) state.SkipWithError("dangling ends were lost: the hour is not perfect");
  if (window_peak > 0 && hour_peak / window_peak > 1.5) state.SkipWithError("the hour holds more than 1.5 x a window's heap");
}
BENCHMARK(BM_PlazaHourStreamed)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// The 10 m × 10 m × 20 s tile periodic in x, y and t at 0.1 characters/m², seeds 1 to 20: each proven perfect by
// the checker; perfect (of 20), the median and largest seconds per seed.
void BM_LoopSeeds(benchmark::State& state) {
  const ThreadLimit limit(2);
  const PatchLibrary lib = builtin_library(builtin_patch_group("locomotion"));
  Environment env;
  env.scene.region = Region{{0, 0}, {10, 10}, 0, 20, {true, true, true}};
  NoProgress quiet;
  std::size_t perfect = 0;
  std::vector<double> seconds;
  double worst_density = 0;
  for (auto _ : state) {
    perfect = 0;
    seconds.clear();
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      Options o;
      o.seed = seed;
      o.annealing.max_failures = 2000;
      o.density.per_m2 = 0.1;
      o.density.report_window_s = 20;
      const TilingResult r = tile(lib, env, {}, o, quiet);
      CheckOptions c;
      c.limits = o.limits;
      c.match = o.match;
      perfect += check_tiling(lib, r.tiling, env, c).perfect() ? 1 : 0;
      seconds.push_back(r.report.seconds);
      const DensityReport d = measure_density(lib, r.tiling, env, o.density, 0, 20);
      worst_density = std::max(worst_density, d.worst_error());
    }
  }
  std::sort(seconds.begin(), seconds.end());
  state.counters["perfect"] = static_cast<double>(perfect);
  state.counters["median_s"] = 0.5 * (seconds[9] + seconds[10]);
  state.counters["max_s"] = seconds.back();
  state.counters["density_worst"] = worst_density;
  if (perfect != 20) state.SkipWithError("not every seed closed every loop");
}
BENCHMARK(BM_LoopSeeds)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
