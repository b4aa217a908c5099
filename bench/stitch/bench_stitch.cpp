// Stitching at scale (issue 4): two 1,000-agent × 300-frame clips, one joint (the matching, the alignment, the
// graph and one solve); the exact matching alone, 1,000 to 10,000 agents (issue 19); and the paper's town job (configs/run-town.yaml) run end to end
// by the `throng` program.
//
// Arguments of stitch_two: sample_step, blend window in frames of the clips' 0.1 s (0: automatic, the default:
// the whole clips unless they exceed max_blend_vertices, then the longest window that fits). {1, 0} is the
// default at every frame: the whole clips would be 599 × 1,000 vertices (more than 17 GB, killed on the 23 GB
// reference machine), so the automatic window shortens to the 60,000-vertex budget (~29 frames per side);
// {1, 30} a 3-s window per side (61,000 vertices); {1, 49} 99,000 vertices; {8, 0} the whole clips sampled
// every 8th frame (77,000 vertices: the budget is lifted for it). Step 1 and step 2 are factorised
// one after the other (one factor in memory at a time). Counters: peak_heap_MB, the largest heap in use during
// the stitch above what was in use before (bench/common/heap.h); max_rss_MB, the process's peak resident
// set so far (monotone: read it for the largest case run); fit_rounds, the assignments of the boundary fit
// (throng/stitch/boundary.h), whose time is matching_s.
//
// Run:   bench_stitch --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include "two_clips.h"

#include <throng/core/assignment.h>
#include <throng/stitch/boundary.h>
#include <throng/stitch/stitch.h>

#include "../common/heap.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using namespace throng;

// bench::two_clips (two_clips.h): two 25 × 40 blocks × 300 frames made apart.
const bench::TwoClips& clips() {
  static const bench::TwoClips c = bench::two_clips(25, 40, 300);
  return c;
}

void stitch_two(benchmark::State& state) {
  stitch::Options o;
  o.sample_step = static_cast<std::size_t>(state.range(0));
  o.blend_window = 0.1 * static_cast<double>(state.range(1));
  o.matching = stitch::Matching::centred;
  if (o.sample_step > 1) o.max_blend_vertices = 0;  // {8, 0}: the whole clips, past the default budget
  (void)clips();  // built before the memory reading
  stitch::Report report;
  double peak_mb = 0;
  for (auto _ : state) {
    bench::HeapPeak peak;
    const stitch::Result r = stitch::stitch_clips(clips().first, clips().second, o);
    peak_mb = std::max(peak_mb, peak.stop());
    report = r.report;
    benchmark::DoNotOptimize(r.crowd.positions.data());
  }
  state.counters["peak_heap_MB"] = peak_mb;
  state.counters["max_rss_MB"] = bench::max_rss_mb();
  state.counters["window_frames"] = static_cast<double>(report.window_first);
  state.counters["solved_samples"] = static_cast<double>(report.solved_samples);
  state.counters["unknowns"] = static_cast<double>(report.unknowns);
  state.counters["fit_rounds"] = static_cast<double>(report.fit_rounds);
  state.counters["matching_s"] = report.matching_seconds;
  state.counters["graph_s"] = report.graph_seconds;
  state.counters["precompute_s"] = report.precompute_seconds;
  state.counters["solve_s"] = report.solve_seconds;
  state.SetLabel(report.factorization);
}
BENCHMARK(stitch_two)->Args({8, 0})->Args({1, 30})->Args({1, 49})->Args({1, 0})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// The boundary matching alone at N agents (two_clips(25, N / 25)'s G last frame against G′'s first), world: as
// placed, 35 m apart and stretched (the paper's round, the hardest), centred: both moved to their centroids.
// planar_*: assign_planar (what stitch runs); dense_*: the O(n³) dense solver over the n × n distances (what it
// ran before; 1,000 and 2,000 only).
struct BoundaryFrames {
  stitch::Points last, first;
};

BoundaryFrames boundary_frames(int agents) {
  const bench::TwoClips k = bench::two_clips(25, agents / 25, 300);
  BoundaryFrames b{stitch::Points(agents, 2), stitch::Points(agents, 2)};
  for (int a = 0; a < agents; ++a) {
    b.last.row(a) = k.first.position(k.first.frame_count() - 1, static_cast<std::size_t>(a)).head<2>().transpose();
    b.first.row(a) = k.second.position(0, static_cast<std::size_t>(a)).head<2>().transpose();
  }
  return b;
}

void planar_matching(benchmark::State& state, stitch::Matching matching) {
  const BoundaryFrames b = boundary_frames(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(stitch::match_boundary(b.last, b.first, matching).total_distance);
}
void dense_matching(benchmark::State& state, stitch::Matching matching) {
  const BoundaryFrames b = boundary_frames(static_cast<int>(state.range(0)));
  const Eigen::RowVector2d shift = matching == stitch::Matching::centred
                                       ? Eigen::RowVector2d(b.first.colwise().mean() - b.last.colwise().mean())
                                       : Eigen::RowVector2d::Zero();
  for (auto _ : state) {
    Eigen::MatrixXd cost(b.last.rows(), b.first.rows());
    for (Eigen::Index i = 0; i < b.last.rows(); ++i)
      for (Eigen::Index k = 0; k < b.first.rows(); ++k) cost(i, k) = (b.last.row(i) + shift - b.first.row(k)).norm();
    benchmark::DoNotOptimize(solve_assignment(cost).cost);
  }
}
BENCHMARK_CAPTURE(planar_matching, world, stitch::Matching::world)
    ->Arg(1000)->Arg(2000)->Arg(5000)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(planar_matching, centred, stitch::Matching::centred)
    ->Arg(1000)->Arg(2000)->Arg(5000)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(dense_matching, world, stitch::Matching::world)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(dense_matching, centred, stitch::Matching::centred)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime();

// The town job as a user runs it: the `throng` program in a scratch folder, the job's paths made absolute.
void town_job(benchmark::State& state) {
  const std::filesystem::path source = THRONG_SOURCE_DIR;
  const std::filesystem::path data = source / "data" / "real";
  std::ifstream in(source / "configs" / "run-town.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string job = text.str();
  auto replace_all = [&](const std::string& from, const std::string& to) {
    for (std::size_t at = job.find(from); at != std::string::npos; at = job.find(from, at + to.size())) job.replace(at, from.size(), to);
  };
  replace_all("configs/", (source / "configs").string() + "/");
  replace_all("data/real/", data.string() + "/");
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "throng_bench_town";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "town.yaml") << job;
  const std::string command = "cd " + dir.string() + " && " + std::string(THRONG_PROGRAM) + " --quiet run town.yaml > /dev/null";
  for (auto _ : state) {
    if (std::system(command.c_str()) != 0) {
      state.SkipWithError("throng run configs/run-town.yaml failed");
      break;
    }
  }
  std::filesystem::remove_all(dir);
}
BENCHMARK(town_job)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
