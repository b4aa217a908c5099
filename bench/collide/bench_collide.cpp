// Collision repair benchmarks (targets on the 2-core reference machine, METHODS.md §1.3 and issue 5):
//  * broad phase against all pairs: random crowds of 1,000 and 5,000 agents × 300 frames (one full contact
//    search each);
//  * the paper's two scenes: two groups bumping (Figure 8, target ≤ 0.2 s) and a circular group forced
//    through a narrow opening (Figure 9, target ≤ 5 s);
//  * two crossing groups of 500 (1,000 agents × 300 frames, target ≤ 30 s).
// Counters: iterations, contacts at the start, and 1 when the run converged.
//
//   bench_collide --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include "scenes.h"

#include <throng/collide/broad_phase.h>
#include <throng/collide/collide.h>
#include <throng/core/parallel.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

using namespace throng;
using namespace throng::collide;

namespace {

const CrowdMotion& random_scene(std::size_t agents) {
  // Density of a busy street: about one agent per 8 m².
  static const CrowdMotion small = scenes::random_crowd(1000, 300, 90.0, 0.06, 7);
  static const CrowdMotion large = scenes::random_crowd(5000, 300, 200.0, 0.06, 7);
  return agents == 1000 ? small : large;
}

void BM_BroadPhase(benchmark::State& state) {
  const CrowdMotion& crowd = random_scene(static_cast<std::size_t>(state.range(0)));
  const auto method = state.range(1) == 0 ? BroadPhase::grid : BroadPhase::all_pairs;
  std::size_t contacts = 0;
  for (auto _ : state) {
    const Contacts c = find_contacts(crowd, {}, 0.0, method);
    contacts = c.pairs.size();
    benchmark::DoNotOptimize(contacts);
  }
  state.counters["contacts"] = static_cast<double>(contacts);
  state.SetLabel(method == BroadPhase::grid ? "grid" : "all pairs");
}
BENCHMARK(BM_BroadPhase)->Args({1000, 0})->Args({1000, 1})->Args({5000, 0})->Args({5000, 1})->Unit(benchmark::kMillisecond);

void repair(benchmark::State& state, const scenes::CollideScene& scene, const Options& options = {}) {
  NoProgress quiet;
  Report report;
  for (auto _ : state) {
    report = resolve_collisions(scene.crowd, scene.obstacles, options, quiet).report;
  }
  state.counters["iterations"] = static_cast<double>(report.iterations);
  state.counters["initial_contacts"] = static_cast<double>(report.initial_pair_contacts + report.initial_obstacle_contacts);
  state.counters["converged"] = report.converged ? 1.0 : 0.0;
  state.counters["solve_s"] = report.solve_seconds;
  state.counters["detect_s"] = report.detect_seconds;
  state.counters["max_speed_ratio"] = report.output_motion.max_speed / std::max(1e-12, report.input_motion.max_speed);
}

// Figure 8: two groups of 25 (5 × 5) bumping, 450 frames (15 s at 30 fps, the paper's frame count).
void BM_Bump(benchmark::State& state) {
  static const auto scene = scenes::bump(5, 450);
  repair(state, scene);
}
BENCHMARK(BM_Bump)->Unit(benchmark::kMillisecond)->UseRealTime();

// Figure 9: a circular group of 61 through a 1.5 m opening, 900 frames (the paper's frame count).
void BM_NarrowOpening(benchmark::State& state) {
  static const auto scene = scenes::narrow_opening(61, 1.5, 900);
  repair(state, scene);
}
BENCHMARK(BM_NarrowOpening)->Unit(benchmark::kMillisecond)->UseRealTime();

// Two groups of 500 crossing, 300 frames.
void BM_Crossing(benchmark::State& state) {
  static const auto scene = scenes::crossing(500, 300);
  repair(state, scene);
}
BENCHMARK(BM_Crossing)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

// The two implementations of the per-trajectory constrained solve (collide.h "Solver"): arg 0 banded (the
// product's), 1 throng/linalg's ConstrainedLeastSquares; on the Figure 8 and Figure 9 scenes.
void BM_TrackMethod(benchmark::State& state) {
  static const auto bump = scenes::bump(5, 450);
  static const auto opening = scenes::narrow_opening(61, 1.5, 900);
  Options options;
  options.track_method = state.range(0) == 0 ? TrackMethod::banded : TrackMethod::linalg;
  state.SetLabel(std::string(state.range(1) == 0 ? "figure 8" : "figure 9") + (state.range(0) == 0 ? ", banded" : ", linalg"));
  repair(state, state.range(1) == 0 ? bump : opening, options);
}
BENCHMARK(BM_TrackMethod)->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({1, 1})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
