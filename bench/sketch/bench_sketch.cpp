// Stroke-driven crowds: agent-steps per second of the simulation step (the speed target, issue 19: ≥ 30 million
// at 10,000 agents in a 100 m × 100 m square on 2 cores; RVO2 does 0.5–1 million there), and the paper's scenarios.
//
// Run: build/<dir>/bench/sketch/bench_sketch --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>
#include <throng/sketch/sketch.h>

#include <cmath>

#include "scenes.h"

using namespace throng::sketch;

namespace {

// N agents at 1 per m² in a square of side √N metres (100 m for 10,000), jittered on a 1 m grid, walking east
// along a main line through the middle between auxiliary lines on the square's edges. Standard distance 1 m.
struct Square {
  Course course;
  AgentParameters agents;
  Options options;
};

Square make_square(std::size_t n) {
  const double side = std::sqrt(static_cast<double>(n));
  const auto per_row = static_cast<std::size_t>(std::ceil(side));
  Square sq;
  sq.options.wide_distance_m = 1.0;
  sq.options.narrow_distance_m = 1.0;
  sq.options.resample_spacing_m = 1.0;
  const double length = 3 * side;  // the course runs on past the square: nobody arrives during a benchmark
  const std::vector<Stroke> strokes{scenes::straight_stroke({0, 0.5 * side}, {length, 0.5 * side}, 2, 1.3),
                                    scenes::straight_stroke({0, 0}, {length, 0}, 2, 1.3),
                                    scenes::straight_stroke({0, side}, {length, side}, 2, 1.3)};
  sq.course = analyse_strokes(strokes, sq.options);
  std::vector<Eigen::Vector2d> start;
  throng::Rng rng(5);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i % per_row) + 0.5, y = static_cast<double>(i / per_row) + 0.5;
    start.emplace_back(x + rng.uniform(-0.2, 0.2), y + rng.uniform(-0.2, 0.2));
  }
  sq.agents = agent_parameters(sq.course, start, sq.options);
  return sq;
}

// One iteration: 250 steps (10 s of crowd time: the crowd packs toward its target lanes, Eq. 2–4, so later steps
// have more neighbours) from the same start; items are agent-steps. From 1,000,000 agents on, 25 steps (1 s of
// crowd time), so that an iteration stays within a minute: time per agent-step, the crowd not yet packed.
void BM_Step(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto threads = static_cast<std::size_t>(state.range(1));
  const Square sq = make_square(n);
  const throng::ThreadLimit limit(threads);
  const int steps = n >= 1000000 ? 25 : 250;
  for (auto _ : state) {
    state.PauseTiming();
    Simulation sim(sq.course, sq.agents, {}, sq.options);
    state.ResumeTiming();
    for (int s = 0; s < steps; ++s) sim.step();
    benchmark::DoNotOptimize(sim.position(0));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n) * steps);
}
BENCHMARK(BM_Step)
    ->ArgNames({"agents", "threads"})
    ->ArgsProduct({{1000, 10000, 100000, 1000000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The paper's experiment end to end (50 agents until everyone has arrived), as a user runs it.
void BM_PaperExperiment(benchmark::State& state) {
  const scenes::SketchScene scene = scenes::paper_experiment();
  std::size_t agent_steps = 0;
  for (auto _ : state) {
    const SimulationResult r = simulate(scene.drawing, scene.scene, scene.options);
    agent_steps += r.step_count * r.motion.agent_count();
    benchmark::DoNotOptimize(r.motion.positions.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(agent_steps));
}
BENCHMARK(BM_PaperExperiment)->Unit(benchmark::kMillisecond)->UseRealTime();

// The large scene: 2,000 agents round pillars, a kiosk, a gate and a moving cart, 60 s of crowd time.
void BM_LargeCrowd(benchmark::State& state) {
  scenes::SketchScene scene = scenes::large_crowd();
  scene.options.duration_s = 60;
  const throng::ThreadLimit limit(static_cast<std::size_t>(state.range(0)));
  std::size_t agent_steps = 0;
  for (auto _ : state) {
    const SimulationResult r = simulate(scene.drawing, scene.scene, scene.options);
    agent_steps += r.step_count * r.motion.agent_count();
    benchmark::DoNotOptimize(r.motion.positions.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(agent_steps));
}
BENCHMARK(BM_LargeCrowd)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
