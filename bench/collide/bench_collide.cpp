// Collision repair benchmarks (targets on the 2-core reference machine, METHODS.md §1.3 and issue 5):
//  * BM_Config: the shipped configs' collide steps on the crowds their earlier steps make (config_scene.h), the
//    user-facing numbers: configs/collide-bump.yaml (two groups bumping, paper Figure 8, target ≤ 0.2 s),
//    configs/collide-narrow-opening.yaml (a circular group forced through an opening, Figure 9, ≤ 5 s) and
//    configs/collide-crossing.yaml (two groups of 500 crossing, 1,000 agents × 301 frames, ≤ 30 s);
//  * broad phase against all pairs: random crowds of 1,000 and 5,000 agents × 300 frames (one full contact
//    search each), and the incremental tracker's update after a typical repair iteration;
//  * BM_Synthetic*: the tests' synthetic scenes (tests/collide/scenes.h), larger than the configs' (Figure 8 as
//    5 × 5 + 5 × 5 agents × 450 frames at 30 fps; Figure 9 as 61 agents × 900 frames through 1.5 m), and the
//    three track solvers on them.
// Counters: iterations, contacts at the start, 1 when the run converged, detection and solve seconds.
//
//   bench_collide --benchmark_filter=BM_Config --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include "config_scene.h"
#include "scenes.h"

#include <throng/collide/broad_phase.h>
#include <throng/collide/collide.h>
#include <throng/collide/contact_tracker.h>
#include <throng/core/parallel.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <memory>
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

// The incremental tracker (contact_tracker.h) after `percent` % of the agents of a random crowd moved by 1 cm at
// every frame (within the skin: the neighbour-list path), against BM_BroadPhase's full search of the same crowd.
void BM_TrackerUpdate(benchmark::State& state) {
  CrowdMotion crowd = random_scene(static_cast<std::size_t>(state.range(0)));
  const auto percent = static_cast<std::size_t>(state.range(1));
  ContactTracker tracker(crowd, {}, 0.0, 0.15);
  double sign = 1.0;
  for (auto _ : state) {
    state.PauseTiming();
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      if (a % 100 >= percent) continue;
      for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
        if (crowd.present(f, a)) crowd.position(f, a).x() += 0.01 * sign;
      }
    }
    sign = -sign;
    state.ResumeTiming();
    tracker.update(crowd);
    benchmark::DoNotOptimize(tracker.contacts().size());
  }
  state.counters["contacts"] = static_cast<double>(tracker.contacts().size());
  state.counters["rebuilt_intervals"] = static_cast<double>(tracker.stats().rebuilt_intervals);
}
BENCHMARK(BM_TrackerUpdate)->Args({1000, 10})->Args({1000, 100})->Args({5000, 10})->Unit(benchmark::kMillisecond);

void repair(benchmark::State& state, const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Options& options) {
  NoProgress quiet;
  Report report;
  for (auto _ : state) {
    report = resolve_collisions(crowd, obstacles, options, quiet).report;
  }
  state.counters["iterations"] = static_cast<double>(report.iterations);
  state.counters["initial_contacts"] = static_cast<double>(report.initial_pair_contacts + report.initial_obstacle_contacts);
  state.counters["converged"] = report.converged ? 1.0 : 0.0;
  state.counters["solve_s"] = report.solve_seconds;
  state.counters["detect_s"] = report.detect_seconds;
  state.counters["max_speed_ratio"] = report.output_motion.max_speed / std::max(1e-12, report.input_motion.max_speed);
}

void repair(benchmark::State& state, const scenes::CollideScene& scene, const Options& options = {}) {
  repair(state, scene.crowd, scene.obstacles, options);
}

// The shipped configs' collide steps (args: 0 bump, 1 narrow opening, 2 crossing; threads, 0 for all), on the
// crowds their sketch and merge steps make; the crowd is made once, outside the timing. With one thread the CPU
// column is the whole work (a measure that a loaded machine disturbs less than the real time).
void BM_Config(benchmark::State& state) {
  ThreadLimit limit(static_cast<std::size_t>(state.range(1)));
  static const char* const names[] = {"collide-bump", "collide-narrow-opening", "collide-crossing"};
  const char* name = names[state.range(0)];
  static std::vector<std::unique_ptr<throng::bench::ConfigScene>> made(3);
  auto& scene = made[static_cast<std::size_t>(state.range(0))];
  if (!scene) scene = std::make_unique<throng::bench::ConfigScene>(throng::bench::config_scene(std::string(THRONG_CONFIG_DIR "/") + name + ".yaml"));
  state.SetLabel(std::string(name) + " (" + std::to_string(scene->crowd.agent_count()) + " x " +
                 std::to_string(scene->crowd.frame_count()) + ")");
  repair(state, scene->crowd, scene->obstacles, scene->options);
}
BENCHMARK(BM_Config)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Config)->ArgsProduct({{2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// Synthetic Figure 8: two groups of 25 (5 × 5) bumping, 450 frames (15 s at 30 fps, the paper's frame count).
void BM_SyntheticBump(benchmark::State& state) {
  static const auto scene = scenes::bump(5, 450);
  repair(state, scene);
}
BENCHMARK(BM_SyntheticBump)->Unit(benchmark::kMillisecond)->UseRealTime();

// Synthetic Figure 9: a circular group of 61 through a 1.5 m opening, 900 frames (the paper's frame count).
void BM_SyntheticNarrowOpening(benchmark::State& state) {
  static const auto scene = scenes::narrow_opening(61, 1.5, 900);
  repair(state, scene);
}
BENCHMARK(BM_SyntheticNarrowOpening)->Unit(benchmark::kMillisecond)->UseRealTime();

// Synthetic crossing: two groups of 500, 300 frames.
void BM_SyntheticCrossing(benchmark::State& state) {
  static const auto scene = scenes::crossing(500, 300);
  repair(state, scene);
}
BENCHMARK(BM_SyntheticCrossing)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

// The three implementations of the per-trajectory constrained solve (collide.h "Solver"): arg 0 eliminate (the
// product's), 1 schur (band factor once, Schur complement), 2 throng/linalg's ConstrainedLeastSquares; on the
// synthetic Figure 8 and Figure 9 scenes.
void BM_TrackMethod(benchmark::State& state) {
  static const auto bump = scenes::bump(5, 450);
  static const auto opening = scenes::narrow_opening(61, 1.5, 900);
  static const char* const names[] = {"eliminate", "schur", "linalg"};
  Options options;
  options.track_method = std::array{TrackMethod::eliminate, TrackMethod::schur, TrackMethod::linalg}[static_cast<std::size_t>(state.range(0))];
  state.SetLabel(std::string(state.range(1) == 0 ? "figure 8, " : "figure 9, ") + names[state.range(0)]);
  repair(state, state.range(1) == 0 ? bump : opening, options);
}
BENCHMARK(BM_TrackMethod)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
