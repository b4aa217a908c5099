// Same input, same bits, whatever the thread count.
#include <throng/formation/formation.h>

#include <throng/core/parallel.h>

#include "fixtures.h"

#include <catch2/catch.hpp>

using namespace throng::formation;

namespace {

Result run(const Problem& p, const Options& o, std::size_t threads) {
  throng::ThreadLimit limit(threads);
  return animate_formation(p, o);
}

}  // namespace

TEST_CASE("one thread and two threads give the same bits: flat formation large enough to run in parallel") {
  Problem p;
  for (int k = 0; k < 3; ++k)
    p.keyframes.push_back(Keyframe{1.5 * k, throng::test::scattered(300, 12.0, 40 + static_cast<std::uint64_t>(k)), {}});
  Options o;
  o.frame_rate_hz = 20;
  const Result one = run(p, o, 1);
  const Result two = run(p, o, 2);
  CHECK(one.motion.positions == two.motion.positions);
  CHECK(one.motion.orientations == two.motion.orientations);
  CHECK(one.motion.actions == two.motion.actions);
}

TEST_CASE("one thread and two threads give the same bits: hierarchy, matching and collision avoidance") {
  Problem p;
  for (int k = 0; k < 2; ++k)
    p.keyframes.push_back(Keyframe{3.0 * k, throng::test::scattered(120, 7.0, 50 + static_cast<std::uint64_t>(k), 0.8), {}});
  Options o;
  o.frame_rate_hz = 20;
  o.auto_group_size = 8;
  o.match_individuals = true;
  o.collision.enabled = true;
  o.collision.min_distance_m = 0.7;
  const Result one = run(p, o, 1);
  const Result two = run(p, o, 2);
  CHECK(one.motion.positions == two.motion.positions);
  CHECK(one.motion.orientations == two.motion.orientations);
  CHECK(one.motion.actions == two.motion.actions);
  CHECK(one.correspondence == two.correspondence);
  CHECK(one.collision.satisfied);
}

TEST_CASE("one thread and two threads give the same bits: an automatic hierarchy of 2,400 (sparse Fiedler vectors, "
          "both solvers, halves bisected in parallel)") {
  const Eigen::MatrixXd start = throng::test::scattered(2400, 40.0, 60, 0.6);
  for (bool reshuffled : {false, true}) {
    INFO("reshuffled " << reshuffled);
    Problem p;
    p.keyframes.push_back(Keyframe{0.0, start, {}});
    // Kept neighbours (a turned, moved copy: a nearly planar summed graph) or unrelated places (an expander).
    p.keyframes.push_back(Keyframe{20.0, reshuffled ? throng::test::scattered(2400, 40.0, 61, 0.6)
                                                    : throng::test::rigid_2d(start, 0.3, {15.0, 0.0}), {}});
    Options o;
    o.frame_rate_hz = 1;
    const Result one = run(p, o, 1);
    const Result two = run(p, o, 2);
    REQUIRE(one.hierarchy.subgroups.size() == 10);  // 2,400 > 2,000: groups of at most 250
    CHECK(one.motion.positions == two.motion.positions);
    CHECK(one.motion.species == two.motion.species);
  }
}
