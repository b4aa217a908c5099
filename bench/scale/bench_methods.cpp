// Every method at scale (issue 19, item 2: "10,000 characters through every method"): collision repair, formation
// control, stitching and time warping, each at N = 1,000, 2,000, 5,000 and 10,000 characters with its default
// options, timing one run per case (Iterations(1)) and its peak heap; after the runs the least-squares growth
// exponents of time and peak heap against N are printed (bench/common/growth_reporter.h) and one log–log picture
// is written, time and memory per method against N (bench/scale/chart.h: methods.csv/json are scale.csv/json in
// the --methods_out folder, the picture scale-methods.svg).
//
// Cases, named methods/<method>/agents:N (the scenes are the ones the per-method benches and tests use, scaled):
//  * collide: tests/collide/scenes.h crossing(N/2, 300), two square groups crossing at right angles, 300 frames
//    (bench_collide's BM_SyntheticCrossing at N = 1,000). Valid: the repair's own flag, converged with no
//    contact left. Issue target at 10,000: ≤ 30 s.
//  * formation: tests/formation/scenes.h marching_crowd(N), 1,000 frames, the automatic hierarchy beyond 2,000
//    individuals (bench_formation's BM_Crowd). Valid: 1,000 frames of finite positions. Target: ≤ 5 s.
//  * stitch: bench/stitch/two_clips.h, two blocks of 25 × N/25 agents × 300 frames (bench_stitch's stitch_two at
//    1,000), default options (automatic window, its vertex budget). Valid: t + t′ − 1 frames of N agents, finite.
//    Target: ≤ 30 s.
//  * timewarp: bench/timewarp/bulge_scene.h, 25 × N/25 walkers × 600 frames (bench_timewarp at 1,000), default
//    options. Valid: finite output, speed deviation not increased. No target.
// A run that throws or fails its check is reported with SkipWithError (and left out of the fits).
// Counters: agents, frames, peak_heap_mb (the heap held at most during the call above what was held before it,
// bench/common/heap.h), max_rss_mb, and the method's own figures.
//
//   bench_methods --methods_agents=1000,2000,5000,10000 --methods_out=out [--benchmark_filter=collide]
#include "../../tests/collide/scenes.h"
#include "../../tests/formation/scenes.h"
#include "../common/growth_reporter.h"
#include "../common/heap.h"
#include "../stitch/two_clips.h"
#include "../timewarp/bulge_scene.h"
#include "chart.h"

#include <throng/collide/collide.h>
#include <throng/core/parallel.h>
#include <throng/formation/formation.h>
#include <throng/process/huge_pages.h>
#include <throng/process/process.h>
#include <throng/stitch/stitch.h>
#include <throng/timewarp/timewarp.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace throng;

bool finite(const CrowdMotion& m) {
  return std::all_of(m.positions.begin(), m.positions.end(), [](double v) { return std::isfinite(v); });
}

// Runs `method` once per iteration under a heap watch; it returns an empty string when its output is valid, else
// why not. Sets the counters the growth reporter and the chart read.
void measure(benchmark::State& state, std::size_t agents, std::size_t frames, const std::function<std::string(benchmark::State&)>& method) {
  const ThreadLimit threads(0);
  double peak = 0;
  for (auto _ : state) {
    std::string failure;
    {
      bench::HeapPeak heap;
      try {
        failure = method(state);
      } catch (const std::exception& e) {
        failure = std::string("threw: ") + e.what();
      }
      peak = std::max(peak, heap.stop());
    }
    if (!failure.empty()) {
      state.SkipWithError(failure.c_str());
      return;
    }
  }
  state.counters["agents"] = static_cast<double>(agents);
  state.counters["individuals"] = static_cast<double>(agents);  // the growth reporter's x
  state.counters["frames"] = static_cast<double>(frames);
  state.counters["peak_heap_mb"] = peak;
  state.counters["memory_MB"] = peak;  // the chart's memory panel
  state.counters["max_rss_mb"] = bench::max_rss_mb();
}

void collide_case(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const collide::scenes::CollideScene scene = collide::scenes::crossing(n / 2, 300);
  measure(state, scene.crowd.agent_count(), scene.crowd.frame_count(), [&](benchmark::State& s) -> std::string {
    NoProgress quiet;
    const collide::Report r = collide::resolve_collisions(scene.crowd, scene.obstacles, collide::Options{}, quiet).report;
    s.counters["iterations"] = static_cast<double>(r.iterations);
    s.counters["initial_contacts"] = static_cast<double>(r.initial_pair_contacts + r.initial_obstacle_contacts);
    s.counters["remaining_contacts"] = static_cast<double>(r.remaining());
    s.counters["solve_s"] = r.solve_seconds;
    s.counters["detect_s"] = r.detect_seconds;
    if (!r.converged || r.remaining() != 0) return "collision repair did not converge: " + std::to_string(r.remaining()) + " contacts left";
    return "";
  });
}

void formation_case(benchmark::State& state) {
  formation::Options options;
  const formation::Problem problem = test::marching_crowd(static_cast<int>(state.range(0)), options.frame_rate_hz);
  std::size_t frames = 0;
  measure(state, static_cast<std::size_t>(problem.keyframes[0].positions.rows()), 1000, [&](benchmark::State& s) -> std::string {
    const auto result = formation::animate_formation(problem, options);
    frames = result.motion.frame_count();
    s.counters["top_groups"] = static_cast<double>(result.hierarchy.subgroups.size());
    if (frames < 1000 || !finite(result.motion)) return "formation output: " + std::to_string(frames) + " frames (1,000 intervals expected) or not finite";
    return "";
  });
}

void stitch_case(benchmark::State& state) {
  const bench::TwoClips clips = bench::two_clips(25, static_cast<int>(state.range(0)) / 25, 300);
  measure(state, clips.first.agent_count(), 2 * 300 - 1, [&](benchmark::State& s) -> std::string {
    const stitch::Result r = stitch::stitch_clips(clips.first, clips.second, stitch::Options{});
    s.counters["window_frames"] = static_cast<double>(r.report.window_first);
    s.counters["unknowns"] = static_cast<double>(r.report.unknowns);
    s.counters["precompute_s"] = r.report.precompute_seconds;
    s.counters["solve_s"] = r.report.solve_seconds;
    s.counters["matching_s"] = r.report.matching_seconds;
    if (r.crowd.agent_count() != clips.first.agent_count() || r.crowd.frame_count() < 2 * 300 - 1 || !finite(r.crowd))
      return "stitch output: " + std::to_string(r.crowd.agent_count()) + " agents × " + std::to_string(r.crowd.frame_count()) + " frames or not finite";
    return "";
  });
}

void timewarp_case(benchmark::State& state) {
  const bench::BulgeScene scene = bench::bulge_scene(25, static_cast<int>(state.range(0)) / 25, 600);
  measure(state, scene.deformed.agent_count(), 600, [&](benchmark::State& s) -> std::string {
    const timewarp::Result r = timewarp::time_warp(scene.deformed, scene.original, timewarp::Options{});
    s.counters["frames_out"] = static_cast<double>(r.report.frames_out);
    s.counters["deviation_before"] = r.report.speed_deviation_before;
    s.counters["deviation_after"] = r.report.speed_deviation_after;
    if (!finite(r.crowd) || r.crowd.agent_count() != scene.deformed.agent_count() || r.report.speed_deviation_after > r.report.speed_deviation_before)
      return "time warp output not finite, agents lost or speed deviation increased";
    return "";
  });
}

// The growth lines, plus the rows of the picture (chart.h).
class MethodsReporter : public bench::GrowthReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    bench::GrowthReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const bool single = run.run_type == Run::RT_Iteration && run.repetitions <= 1;
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if (run.error_occurred || !(single || median)) continue;
      ::scale::Row row;
      row.name = run.run_name.function_name + "/" + run.run_name.args;
      row.repetitions = static_cast<int>(run.repetitions);
      row.seconds = run.GetAdjustedRealTime() * benchmark::GetTimeUnitMultiplier(run.time_unit);
      for (const auto& [name, counter] : run.counters) row.values[name] = counter.value;
      rows.push_back(std::move(row));
    }
  }
  std::vector<::scale::Row> rows;
};

std::vector<long> parse_sizes(const std::string& text) {
  std::vector<long> sizes;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) sizes.push_back(std::stol(item));
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  throng::restart_with_huge_pages(argv);  // as the program does (throng/process/huge_pages.h)
  const throng::Process process;
  std::vector<long> sizes{1000, 2000, 5000, 10000};
  std::filesystem::path out = "out";
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--methods_agents=", 0) == 0) {
      sizes = parse_sizes(a.substr(std::strlen("--methods_agents=")));
    } else if (a.rfind("--methods_out=", 0) == 0) {
      out = a.substr(std::strlen("--methods_out="));
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  const std::pair<const char*, void (*)(benchmark::State&)> methods[] = {
      {"methods/collide", collide_case}, {"methods/formation", formation_case}, {"methods/stitch", stitch_case}, {"methods/timewarp", timewarp_case}};
  for (const auto& [name, fn] : methods) {
    auto* b = benchmark::RegisterBenchmark(name, fn)->ArgName("agents")->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
    for (const long n : sizes) b->Arg(n);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  MethodsReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  if (!reporter.rows.empty()) ::scale::write_results(out, reporter.rows);
  benchmark::Shutdown();
  return 0;
}
