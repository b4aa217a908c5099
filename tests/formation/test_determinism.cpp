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
  CHECK(one.correspondence == two.correspondence);
  CHECK(one.collision.satisfied);
}
