// Collision repair checked by the brute-force checker: no pair closer than its clearance, no point inside an
// obstacle, pins unchanged; the same bits for 1 and 2 threads; an impossible scene ends with a report.
#include "checker.h"
#include "scenes.h"

#include <throng/collide/collide.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <catch2/catch.hpp>

using namespace throng;
using namespace throng::collide;

namespace {

NoProgress quiet;

std::vector<std::size_t> ends(const CrowdMotion& crowd) { return {0, crowd.frame_count() - 1}; }

void require_clean(const scenes::CollideScene& scene, const Result& result, double margin) {
  INFO(summary(result.report));
  REQUIRE(result.report.converged);
  CHECK(result.report.remaining() == 0);
  CHECK(check::min_pair_slack(result.crowd, margin) >= -1e-9);
  if (!scene.obstacles.empty()) CHECK(check::min_obstacle_slack(result.crowd, scene.obstacles, margin) >= -1e-9);
  CHECK(check::changed_vertices(scene.crowd, result.crowd, ends(scene.crowd)) == 0);  // pins at both ends
  CHECK(result.report.min_pair_gap >= margin - 1e-9);
}

}  // namespace

TEST_CASE("two groups bumping into each other are separated, ends kept (paper Figure 8)") {
  const auto scene = scenes::bump(3, 120);
  REQUIRE(check::min_pair_slack(scene.crowd, 0.0) < -0.3);  // they do collide, deeply
  Options options;
  const Result result = resolve_collisions(scene.crowd, {}, options, quiet);
  require_clean(scene, result, 0.0);
  CHECK(result.report.initial_pair_contacts > 5);
  CHECK(result.report.moved_agents > 5);
  CHECK(result.report.iterations > 1);
  CHECK(result.crowd.ids == scene.crowd.ids);
  CHECK(result.crowd.radii == scene.crowd.radii);
}

TEST_CASE("a margin widens the clearance") {
  const auto scene = scenes::bump(2, 90);
  Options options;
  options.margin = 0.3;
  const Result result = resolve_collisions(scene.crowd, {}, options, quiet);
  require_clean(scene, result, 0.3);
}

TEST_CASE("a circular group is forced through a narrow opening (paper Figure 9)") {
  const auto scene = scenes::narrow_opening(19, 2.4, 300);
  REQUIRE(check::min_obstacle_slack(scene.crowd, scene.obstacles, 0.0) < -0.4);  // through the walls
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, Options{}, quiet);
  require_clean(scene, result, 0.0);
  CHECK(result.report.initial_obstacle_contacts > 5);
}

TEST_CASE("the nearest-boundary pull clears trajectories grazing obstacles") {
  scenes::CollideScene scene = scenes::bump(2, 60);
  scene.obstacles.push_back({Circle{{0.0, 1.15}, 0.4}, {}, "post"});
  scene.obstacles.push_back({ConvexPolygon{{{-1.0, -2.2}, {1.0, -2.2}, {0.0, -0.4}}}, {}, "block"});
  Options options;
  options.obstacle_pull = ObstaclePull::nearest;
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, options, quiet);
  REQUIRE(result.report.initial_obstacle_contacts > 0);
  require_clean(scene, result, 0.0);
}

TEST_CASE("moving obstacles are avoided") {
  scenes::CollideScene scene = scenes::bump(2, 90);
  scene.obstacles.push_back({Circle{{0.0, 0.0}, 0.7}, {{0.0, {0.0, -6.0}, 0.0}, {3.0, {0.0, 6.0}, 0.0}}, "cart"});
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, Options{}, quiet);
  REQUIRE(result.report.initial_obstacle_contacts > 0);
  require_clean(scene, result, 0.0);
}

TEST_CASE("fixed agents do not move and pins off lets the ends move") {
  const auto scene = scenes::bump(2, 60);
  Options options;
  options.fixed_agents = {0, 5};
  const Result result = resolve_collisions(scene.crowd, {}, options, quiet);
  require_clean(scene, result, 0.0);
  std::vector<char> fixed(scene.crowd.agent_count(), 0);
  fixed[0] = fixed[5] = 1;
  CHECK(check::changed_vertices(scene.crowd, result.crowd, {}, fixed) == 0);

  options.fixed_agents.clear();
  options.pin_ends = false;
  const Result free = resolve_collisions(scene.crowd, {}, options, quiet);
  REQUIRE(free.report.converged);
  CHECK(check::min_pair_slack(free.crowd, 0.0) >= -1e-9);
  CHECK(check::changed_vertices(scene.crowd, free.crowd, ends(scene.crowd)) > 0);
}

TEST_CASE("agents entering and leaving (real-data presence) are repaired where present") {
  scenes::CollideScene scene;
  scene.crowd = scenes::random_crowd(40, 50, 6.0, 0.05, 3);
  const Result result = resolve_collisions(scene.crowd, {}, Options{}, quiet);
  INFO(summary(result.report));
  REQUIRE(result.report.initial_pair_contacts > 0);
  // Pairs that overlap at a pinned first or last present frame cannot be resolved; everything else must be.
  if (!result.report.converged) CHECK(result.report.stuck_contacts == result.report.remaining());
  for (std::size_t f = 0; f < scene.crowd.frame_count(); ++f) {
    for (std::size_t a = 0; a < scene.crowd.agent_count(); ++a) CHECK(scene.crowd.present(f, a) == result.crowd.present(f, a));
  }
}

TEST_CASE("1 and 2 threads give the same bits") {
  const auto scene = scenes::crossing(30, 150);
  Result one, two;
  {
    ThreadLimit limit(1);
    one = resolve_collisions(scene.crowd, {}, Options{}, quiet);
  }
  {
    ThreadLimit limit(2);
    two = resolve_collisions(scene.crowd, {}, Options{}, quiet);
  }
  INFO(summary(one.report));
  REQUIRE(one.report.converged);
  CHECK(one.report.iterations == two.report.iterations);
  CHECK(one.crowd.positions == two.crowd.positions);
}

TEST_CASE("two pinned agents on top of each other end with a report, not a hang") {
  CrowdMotion crowd = CrowdMotion::with_shape(20, 3, 0.25);
  for (std::size_t f = 0; f < 20; ++f) {
    crowd.times[f] = 0.1 * static_cast<double>(f);
    crowd.position(f, 0) = Eigen::Vector3d(0.1 * static_cast<double>(f), 0, 0);
    crowd.position(f, 1) = Eigen::Vector3d(0.1 * static_cast<double>(f), 0.1, 0);  // 0.1 m apart all along
    crowd.position(f, 2) = Eigen::Vector3d(0, 5, 0);
  }
  Options options;
  options.max_iterations = 500;
  const Result result = resolve_collisions(crowd, {}, options, quiet);
  INFO(summary(result.report));
  CHECK(!result.report.converged);
  CHECK(result.report.pair_contacts == 1);
  CHECK(result.report.stuck_contacts == 1);
  CHECK(result.report.stop_reason == "only stuck contacts left");
  CHECK(result.report.iterations < options.max_iterations);
  CHECK(check::changed_vertices(crowd, result.crowd, {0, 19}) == 0);
  // Between the pinned ends they were pushed apart.
  CHECK((result.crowd.position(10, 0) - result.crowd.position(10, 1)).norm() >= 0.5 - 1e-9);

  // Fully fixed agents cannot move at all: stuck from the start, no solve.
  options.fixed_agents = {0, 1};
  const Result fixed = resolve_collisions(crowd, {}, options, quiet);
  CHECK(!fixed.report.converged);
  CHECK(fixed.report.iterations == 0);
  CHECK(fixed.crowd.positions == crowd.positions);
}

TEST_CASE("the iteration cap stops a run and says so") {
  const auto scene = scenes::bump(3, 120);
  Options options;
  options.max_iterations = 2;
  const Result result = resolve_collisions(scene.crowd, {}, options, quiet);
  CHECK(!result.report.converged);
  CHECK(result.report.iterations == 2);
  CHECK(result.report.stop_reason == "iteration cap reached");
  CHECK(result.report.remaining() > 0);
  CHECK(summary(result.report).find("iteration cap reached") != std::string::npos);
}

TEST_CASE("bad options and unknown fixed agents are ConfigErrors") {
  const auto scene = scenes::bump(2, 30);
  auto fails = [&](auto change) {
    Options o;
    change(o);
    CHECK_THROWS_AS(resolve_collisions(scene.crowd, {}, o, quiet), ConfigError);
  };
  fails([](Options& o) { o.margin = -0.1; });
  fails([](Options& o) { o.push_fraction = 0.0; });
  fails([](Options& o) { o.push_fraction = 1.5; });
  fails([](Options& o) { o.max_iterations = 0; });
  fails([](Options& o) { o.spread = 0.5; });
  fails([](Options& o) { o.fixed_agents = {999}; });
}
