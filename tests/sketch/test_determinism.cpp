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
