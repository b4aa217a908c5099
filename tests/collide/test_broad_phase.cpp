// The broad phase reports exactly the all-pairs set (same pairs, same moments, same values), whatever the
// thread count, and agrees with brute-force sampling.
#include "checker.h"
#include "same_contacts.h"
#include "scenes.h"

#include <throng/collide/broad_phase.h>
#include <throng/core/parallel.h>

#include <catch2/catch.hpp>

#include <cmath>

using namespace throng;
using namespace throng::collide;

namespace {

using check::require_same_contacts;
using scenes::scattered_obstacles;

}  // namespace

TEST_CASE("broad phase equals all pairs on random crowds") {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    INFO("seed " << seed);
    const CrowdMotion crowd = scenes::random_crowd(120, 40, 15.0, 0.08 * static_cast<double>(seed), seed);
    const auto obstacles = scattered_obstacles();
    for (double margin : {0.0, 0.3}) {
      const Contacts grid = find_contacts(crowd, obstacles, margin, BroadPhase::grid);
      const Contacts all = find_contacts(crowd, obstacles, margin, BroadPhase::all_pairs);
      REQUIRE(grid.pairs.size() > 10);
      REQUIRE(!grid.obstacles.empty());
      require_same_contacts(grid, all);
      if (all.min_pair_gap < margin) CHECK(grid.min_pair_gap == all.min_pair_gap);
    }
  }
}

TEST_CASE("broad phase agrees with brute-force sampling") {
  const CrowdMotion crowd = scenes::random_crowd(60, 30, 10.0, 0.1, 9);
  const Contacts found = find_contacts(crowd, {}, 0.1, BroadPhase::grid);
  // The pairs found are exactly those whose sampled distance falls below the clearance (away from the edge).
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
    for (std::size_t b = a + 1; b < crowd.agent_count(); ++b) {
      CrowdMotion two = CrowdMotion::with_shape(crowd.frame_count(), 2);
      two.times = crowd.times;
      for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
        two.position(f, 0) = crowd.position(f, a);
        two.position(f, 1) = crowd.position(f, b);
      }
      two.radii = {crowd.radii[a], crowd.radii[b]};
      const double slack = check::min_pair_slack(two, 0.1, 64);
      const bool reported = std::any_of(found.pairs.begin(), found.pairs.end(),
                                        [&](const PairContact& c) { return c.a == a && c.b == b; });
      if (slack < -1e-6) CHECK(reported);
      if (slack > 1e-3) CHECK(!reported);
    }
  }
}

TEST_CASE("broad phase restricted to flagged agents equals the filtered all-pairs set") {
  const CrowdMotion crowd = scenes::random_crowd(100, 30, 12.0, 0.15, 5);
  std::vector<char> flags(crowd.agent_count(), 0);
  for (std::size_t a = 0; a < flags.size(); a += 7) flags[a] = 1;
  const Contacts some = find_contacts(crowd, scattered_obstacles(), 0.2, BroadPhase::grid, flags);
  Contacts expected = find_contacts(crowd, scattered_obstacles(), 0.2, BroadPhase::all_pairs);
  std::erase_if(expected.pairs, [&](const PairContact& c) { return flags[c.a] == 0 && flags[c.b] == 0; });
  std::erase_if(expected.obstacles, [&](const ObstacleContact& c) { return flags[c.agent] == 0; });
  REQUIRE(!expected.pairs.empty());
  require_same_contacts(some, expected);
}

TEST_CASE("broad phase does not depend on the thread count") {
  const CrowdMotion crowd = scenes::random_crowd(300, 60, 25.0, 0.1, 21);
  Contacts one, two;
  {
    ThreadLimit limit(1);
    one = find_contacts(crowd, scattered_obstacles(), 0.1);
  }
  {
    ThreadLimit limit(2);
    two = find_contacts(crowd, scattered_obstacles(), 0.1);
  }
  require_same_contacts(one, two);
  CHECK(one.min_pair_gap == two.min_pair_gap);
  CHECK(one.min_obstacle_gap == two.min_obstacle_gap);
}
