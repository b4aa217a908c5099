// Same input and seed give the same bits whatever the thread count (two buffers, fixed neighbour order).
#include <throng/core/parallel.h>
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>
#include <cstring>

#include "scenes.h"

using namespace throng::sketch;

namespace {

SimulationResult run_large(std::size_t threads) {
  const throng::ThreadLimit limit(threads);
  scenes::SketchScene large = scenes::large_crowd();
  large.options.duration_s = 4;
  return simulate(large.drawing, large.scene, large.options);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("1 thread and 2 threads give identical positions, bit for bit") {
  const SimulationResult one = run_large(1);
  const SimulationResult two = run_large(2);
  REQUIRE(one.motion.agent_count() >= 2000);  // several parallel tasks per step
  CHECK(same_bits(one.motion.positions, two.motion.positions));
  CHECK(same_bits(one.motion.orientations, two.motion.orientations));
  CHECK(one.motion.actions == two.motion.actions);
  CHECK(same_bits(one.arrival_time_s, two.arrival_time_s));
  CHECK(one.step_count == two.step_count);
  // And the run is not trivially still: the crowd moved (1.4 m/s for 4 s, less where it is dense).
  const std::size_t last = one.motion.frame_count() - 1;
  double moved = 0;
  for (std::size_t a = 0; a < one.motion.agent_count(); ++a) {
    moved += (one.motion.position(last, a) - one.motion.position(0, a)).norm();
  }
  CHECK(moved / static_cast<double>(one.motion.agent_count()) > 3.0);
}

TEST_CASE("1 thread and 2 threads give identical whole runs past every obstacle to the end, stop and remove") {
  // The large scene with 1,000 agents (two parallel tasks per step) until everyone has arrived: sliding round
  // the pillars, the kiosk, the gate and the cart, arrival, standing (stop) and removal (remove) all run.
  for (const EndOfPath mode : {EndOfPath::stop, EndOfPath::remove}) {
    INFO((mode == EndOfPath::stop ? "stop" : "remove"));
    scenes::SketchScene large = scenes::large_crowd();
    large.options.agent_count = 1000;
    large.options.duration_s = 0;
    large.options.output_rate_hz = 2;
    large.options.end_of_path = mode;
    const auto run = [&](std::size_t threads) {
      const throng::ThreadLimit limit(threads);
      return simulate(large.drawing, large.scene, large.options);
    };
    const SimulationResult one = run(1);
    const SimulationResult two = run(2);
    REQUIRE(one.finished);
    CHECK(same_bits(one.motion.positions, two.motion.positions));
    CHECK(same_bits(one.motion.times, two.motion.times));
    CHECK(same_bits(one.arrival_time_s, two.arrival_time_s));
    CHECK(one.step_count == two.step_count);
    CHECK(one.unresolved_obstacle_contacts == two.unresolved_obstacle_contacts);
    CHECK(two.finished);
    // The run reached every obstacle: some agent came within the push distance of each one.
    const double reach = large.options.agent_radius_m + large.options.obstacle_distance_m;
    for (const auto& obstacle : large.scene.obstacles) {
      INFO(obstacle.name);
      double closest = 1e300;
      for (std::size_t f = 0; f < one.motion.frame_count(); ++f) {
        for (std::size_t a = 0; a < one.motion.agent_count(); ++a) {
          if (!one.motion.present(f, a)) continue;
          const Eigen::Vector2d p = one.motion.position(f, a).head<2>();
          closest = std::min(closest, distance_to(obstacle, p, one.motion.times[f]).signed_distance);
        }
      }
      CHECK(closest < reach);
    }
    // Everyone arrived; with remove, nobody is left in the last frame.
    const std::size_t last = one.motion.frame_count() - 1;
    std::size_t present = 0;
    for (std::size_t a = 0; a < one.motion.agent_count(); ++a) present += one.motion.present(last, a) ? 1 : 0;
    CHECK(present == (mode == EndOfPath::stop ? 1000U : 0U));
  }
}

TEST_CASE("the seed changes the irregular crowd, and the same seed repeats it") {
  scenes::SketchScene paper = scenes::paper_experiment();
  paper.options.duration_s = 50;  // into the irregular part
  const SimulationResult a = simulate(paper.drawing, paper.scene, paper.options);
  const SimulationResult again = simulate(paper.drawing, paper.scene, paper.options);
  paper.options.seed += 1;
  const SimulationResult other = simulate(paper.drawing, paper.scene, paper.options);
  CHECK(same_bits(a.motion.positions, again.motion.positions));
  CHECK_FALSE(same_bits(a.motion.positions, other.motion.positions));
}
