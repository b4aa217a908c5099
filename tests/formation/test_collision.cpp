// Collision avoidance (§4.3): social forces then smoothing that keeps a minimum distance.
#include <throng/formation/formation.h>

#include "fixtures.h"

#include <catch2/catch.hpp>

using namespace throng::formation;

namespace {

// 30 individuals, target rows a shuffled copy of a different scatter: paths cross in the middle.
Problem crossing() {
  Problem p;
  const Eigen::MatrixXd a = throng::test::scattered(30, 4.0, 5, 0.9);
  const Eigen::MatrixXd b = throng::test::scattered(30, 4.0, 6, 0.9);
  Eigen::MatrixXd shuffled(30, 2);
  for (int i = 0; i < 30; ++i) shuffled.row(i) = b.row((i * 7) % 30);
  p.keyframes.push_back(Keyframe{0.0, a, {}});
  p.keyframes.push_back(Keyframe{4.0, shuffled.rowwise() + Eigen::RowVector2d(1.0, 0.0), {}});
  p.keyframes.push_back(Keyframe{8.0, a.rowwise() + Eigen::RowVector2d(2.0, 1.0), {}});
  return p;
}

}  // namespace

TEST_CASE("collision avoidance meets its minimum distance and keeps the keyframes") {
  const Problem p = crossing();
  Options o;
  o.frame_rate_hz = 15;
  const Result plain = animate_formation(p, o);
  const double min_distance = 0.8;
  REQUIRE(throng::test::closest_pair_distance(plain.motion) < 0.5 * min_distance);  // the spectral paths collide

  o.collision.enabled = true;
  o.collision.min_distance_m = min_distance;
  const Result avoided = animate_formation(p, o);
  CHECK(avoided.collision.ran);
  CHECK(avoided.collision.satisfied);
  CHECK(throng::test::closest_pair_distance(avoided.motion) >= min_distance * (1 - 1e-6));
  CHECK(avoided.collision.closest_m >= min_distance * (1 - 1e-6));
  // Keyframes are kept exactly (pinned), and the paths stay near the spectral ones.
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t f = k * 60;
    CHECK((avoided.motion.frame(f).leftCols(2) - p.keyframes[k].positions).cwiseAbs().maxCoeff() <= 1e-12 * 10);
  }
  double farthest = 0.0, mean = 0.0;
  for (std::size_t f = 0; f < avoided.motion.frame_count(); ++f) {
    farthest = std::max(farthest, (avoided.motion.frame(f) - plain.motion.frame(f)).rowwise().norm().maxCoeff());
    mean += (avoided.motion.frame(f) - plain.motion.frame(f)).rowwise().norm().mean() / static_cast<double>(avoided.motion.frame_count());
  }
  INFO("largest shift " << farthest << " m, mean shift " << mean << " m");
  CHECK(farthest == Catch::Detail::Approx(avoided.collision.largest_shift_m));
  // Everyone crosses everyone here (a shuffle at 0.4 of the densest packing): some must detour, but on average
  // individuals stay within the minimum distance of their spectral paths, and nobody leaves the formation.
  CHECK(mean < min_distance);
  CHECK(farthest < 4.0);
  // Smooth: no frame-to-frame jump much larger than the spectral paths' largest step.
  double plain_step = 0.0, step = 0.0;
  for (std::size_t f = 1; f < plain.motion.frame_count(); ++f) {
    plain_step = std::max(plain_step, (plain.motion.frame(f) - plain.motion.frame(f - 1)).rowwise().norm().maxCoeff());
    step = std::max(step, (avoided.motion.frame(f) - avoided.motion.frame(f - 1)).rowwise().norm().maxCoeff());
  }
  CHECK(step < 3.0 * plain_step);
}

TEST_CASE("keyframes closer than the collision distance are an InputError") {
  Problem p = crossing();
  Options o;
  o.collision.enabled = true;
  o.collision.min_distance_m = 2.0;  // the scatters are only 0.9 m apart
  CHECK_THROWS_WITH(animate_formation(p, o), Catch::Matchers::Contains("closer than collision.min_distance"));
}
