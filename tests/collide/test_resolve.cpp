// Collision repair checked by the brute-force checker: no pair closer than its clearance, no point inside an
// obstacle, pins unchanged; the same bits for 1 and 2 threads; an impossible scene ends with a report.
#include "checker.h"
#include "scenes.h"

#include <throng/check/motion_check.h>
#include <throng/collide/collide.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace throng;
using namespace throng::collide;
namespace motion = throng::check;
namespace brute = throng::collide::check;  // tests/collide/checker.h

namespace {

NoProgress quiet;

std::vector<std::size_t> ends(const CrowdMotion& crowd) { return {0, crowd.frame_count() - 1}; }

// The repair's mechanics without the plausibility limits (collide.h "Limits"), for the cases below whose point
// is how the repair pushes, pins, fixes and classifies, on scenes a person could not walk within the limits:
// 2-s clips of groups passing through each other (or through an agent that may not move: the other must
// sidestep alone at 1.6 m/s with 25 % of speed to spare), two agents 0.1 m apart separated within a second of
// their pins, a pedestrian standing inside a pillar at both ends. The limits' own tests are the paper scenes
// (below) and the shipped configs and recorded crowds (tests/cli).
Options unlimited() {
  Options o;
  o.max_speed_ratio = 0;
  o.max_acceleration = 0;
  return o;
}

// The independent checker's verdict on `repaired` against its input: speed ≤ 1.25 × the input's fastest,
// acceleration ≤ 8 m/s² (99th percentile ≤ 3 m/s²) or the input's own, turning unlimited (the repair does not
// bound it). Empty when within the limits.
std::string plausibility(const CrowdMotion& input, const CrowdMotion& repaired) {
  const motion::Statistics in = motion::measure(input, {}, motion::Settings{});
  motion::Limits limits = motion::limits_from_reference(in, motion::Limits{}, 1.25);
  limits.max_turning_rate = limits.turning_rate_p99 = motion::unlimited;
  limits.max_pair_contacts.reset();
  std::string broken;
  for (const motion::Violation& v : motion::check(motion::measure(repaired, {}, motion::Settings{}), limits).violations) {
    broken += motion::describe(v) + "; ";
  }
  return broken;
}

void require_clean(const scenes::CollideScene& scene, const Result& result, double margin) {
  INFO(summary(result.report));
  REQUIRE(result.report.converged);
  CHECK(result.report.remaining() == 0);
  CHECK(brute::min_pair_slack(result.crowd, margin) >= -1e-9);
  if (!scene.obstacles.empty()) CHECK(brute::min_obstacle_slack(result.crowd, scene.obstacles, margin) >= -1e-9);
  CHECK(brute::changed_vertices(scene.crowd, result.crowd, ends(scene.crowd)) == 0);  // pins at both ends
  CHECK(result.report.min_pair_gap >= margin - 1e-9);
}

}  // namespace

TEST_CASE("two groups bumping into each other are separated, ends kept (paper Figure 8)") {
  const auto scene = scenes::bump(3, 120);
  REQUIRE(brute::min_pair_slack(scene.crowd, 0.0) < -0.3);  // they do collide, deeply
  Options options;
  const Result result = resolve_collisions(scene.crowd, {}, options, quiet);
  require_clean(scene, result, 0.0);
  CHECK(result.report.initial_pair_contacts > 5);
  CHECK(result.report.moved_agents > 5);
  CHECK(result.report.iterations >= 1);  // one full push per contact can clear the scene at once
  CHECK(result.crowd.ids == scene.crowd.ids);
  CHECK(result.crowd.radii == scene.crowd.radii);
  CHECK(plausibility(scene.crowd, result.crowd).empty());
  // The paper's 10 % steps take several iterations to the same end.
  Options steps;
  steps.push_size = PushSize::fraction;
  const Result stepped = resolve_collisions(scene.crowd, {}, steps, quiet);
  require_clean(scene, stepped, 0.0);
  CHECK(stepped.report.iterations > 1);
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
  REQUIRE(brute::min_obstacle_slack(scene.crowd, scene.obstacles, 0.0) < -0.4);  // through the walls
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, Options{}, quiet);
  require_clean(scene, result, 0.0);
  CHECK(result.report.initial_obstacle_contacts > 5);
}

TEST_CASE("the nearest-boundary pull clears trajectories grazing obstacles") {
  scenes::CollideScene scene = scenes::bump(2, 60);
  scene.obstacles.push_back({Circle{{0.0, 1.15}, 0.4}, {}, "post"});
  scene.obstacles.push_back({ConvexPolygon{{{-1.0, -2.2}, {1.0, -2.2}, {0.0, -0.4}}}, {}, "block"});
  Options options = unlimited();
  options.obstacle_pull = ObstaclePull::nearest;
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, options, quiet);
  REQUIRE(result.report.initial_obstacle_contacts > 0);
  require_clean(scene, result, 0.0);
}

// One agent walks up to a 10 m wall (0.4 m thick along y = 0, from x = −5 to 5) 1.5 m from its east end,
// reaches y = `reach` and walks back: 6 s at 30 fps, y = −3 + (3 + reach) sin(π t / 6), x = 3.5 + 0.1 t.
scenes::CollideScene wall_clip(double reach, double radius) {
  scenes::CollideScene s;
  s.crowd = CrowdMotion::with_shape(181, 1, radius);
  for (std::size_t f = 0; f < 181; ++f) {
    const double t = static_cast<double>(f) / 30.0;
    s.crowd.times[f] = t;
    s.crowd.position(f, 0) = Eigen::Vector3d(3.5 + 0.1 * t, -3.0 + (3.0 + reach) * std::sin(M_PI * t / 6.0), 0.0);
  }
  s.obstacles.push_back({Wall{{-5.0, 0.0}, {5.0, 0.0}, 0.4}, {}, "wall"});
  return s;
}

TEST_CASE("an agent that clips a wall is pushed back to the side it came from, never through or round its end") {
  // It reaches y = 0.1, past the wall's middle line: the nearest boundary there is the far face. Going round
  // the east end would move it at least 1.5 m along x.
  const auto scene = wall_clip(0.1, 0.25);
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, Options{}, quiet);
  require_clean(scene, result, 0.0);
  double farthest_north = -1e9;
  for (std::size_t f = 0; f < result.crowd.frame_count(); ++f) farthest_north = std::max(farthest_north, result.crowd.position(f, 0).y());
  CHECK(farthest_north <= -0.45 + 1e-9);  // on its own side: 0.2 m half-thickness + 0.25 m radius
  // Back by the depth (0.1 + 0.2 + 0.25 m) and a push's extra, spread smoothly: not along the wall.
  CHECK(result.report.max_displacement <= 0.55 + 0.1);
  CHECK(plausibility(scene.crowd, result.crowd).empty());

  // The rule across its motion (the previous default) takes it along the wall, round the near end.
  Options across;
  across.obstacle_pull = ObstaclePull::sideways;
  const Result round = resolve_collisions(scene.crowd, scene.obstacles, across, quiet);
  CHECK(round.report.max_displacement > 1.5);
}

TEST_CASE("the default displacement bound follows the agents' size, and a contact beyond it is reported and left") {
  // Up to the wall's far face (reach 0.2 m): 0.2 + 0.2 + r back. Radius 0.25: 0.65 m, within 8 radii (2 m),
  // repaired. Radius 0.05: 0.45 m, beyond 8 radii (0.4 m): left, reported, nothing forced — and repaired when
  // the job asks for more room.
  const auto wide = wall_clip(0.2, 0.25);
  require_clean(wide, resolve_collisions(wide.crowd, wide.obstacles, Options{}, quiet), 0.0);

  const auto thin = wall_clip(0.2, 0.05);
  const Result left = resolve_collisions(thin.crowd, thin.obstacles, Options{}, quiet);
  INFO(summary(left.report));
  CHECK(!left.report.converged);
  CHECK(left.report.obstacle_contacts > 0);
  CHECK(left.report.abandoned_contacts + left.report.stuck_contacts == left.report.remaining());
  CHECK(left.report.max_displacement <= 8 * 0.05 + 1e-9);
  Options room;
  room.max_displacement = 1.0;
  const Result roomy = resolve_collisions(thin.crowd, thin.obstacles, room, quiet);
  require_clean(thin, roomy, 0.0);
  double farthest_north = -1e9;
  for (std::size_t f = 0; f < roomy.crowd.frame_count(); ++f) farthest_north = std::max(farthest_north, roomy.crowd.position(f, 0).y());
  CHECK(farthest_north <= -0.25 + 1e-9);
}

TEST_CASE("moving obstacles are avoided") {
  scenes::CollideScene scene = scenes::bump(2, 90);
  scene.obstacles.push_back({Circle{{0.0, 0.0}, 0.7}, {{0.0, {0.0, -6.0}, 0.0}, {3.0, {0.0, 6.0}, 0.0}}, "cart"});
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, unlimited(), quiet);
  REQUIRE(result.report.initial_obstacle_contacts > 0);
  require_clean(scene, result, 0.0);
}

TEST_CASE("fixed agents do not move and pins off lets the ends move") {
  const auto scene = scenes::bump(2, 60);
  Options options = unlimited();
  options.fixed_agents = {0, 5};
  const Result result = resolve_collisions(scene.crowd, {}, options, quiet);
  require_clean(scene, result, 0.0);
  std::vector<char> fixed(scene.crowd.agent_count(), 0);
  fixed[0] = fixed[5] = 1;
  CHECK(brute::changed_vertices(scene.crowd, result.crowd, {}, fixed) == 0);

  options.fixed_agents.clear();
  options.pin_ends = false;
  const Result free = resolve_collisions(scene.crowd, {}, options, quiet);
  REQUIRE(free.report.converged);
  CHECK(brute::min_pair_slack(free.crowd, 0.0) >= -1e-9);
  CHECK(brute::changed_vertices(scene.crowd, free.crowd, ends(scene.crowd)) > 0);
}

TEST_CASE("agents entering and leaving (real-data presence) are repaired where present") {
  scenes::CollideScene scene;
  scene.crowd = scenes::random_crowd(40, 50, 6.0, 0.05, 3);
  // Pairs that overlap at a pinned first or last present frame cannot be resolved; everything else must be
  // (without the limits: the random walks' 1.5 m/s steps in random directions leave no room within them).
  const Result result = resolve_collisions(scene.crowd, {}, unlimited(), quiet);
  INFO(summary(result.report));
  REQUIRE(result.report.initial_pair_contacts > 0);
  if (!result.report.converged) CHECK(result.report.stuck_contacts == result.report.remaining());
  for (std::size_t f = 0; f < scene.crowd.frame_count(); ++f) {
    for (std::size_t a = 0; a < scene.crowd.agent_count(); ++a) CHECK(scene.crowd.present(f, a) == result.crowd.present(f, a));
  }
  // With the limits, what is left is stuck or abandoned, and nothing beyond them was forced.
  const Result limited = resolve_collisions(scene.crowd, {}, Options{}, quiet);
  INFO(summary(limited.report));
  CHECK(limited.report.stuck_contacts + limited.report.abandoned_contacts == limited.report.remaining());
  CHECK(plausibility(scene.crowd, limited.crowd).empty());
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
  Options options = unlimited();
  options.max_iterations = 500;
  const Result result = resolve_collisions(crowd, {}, options, quiet);
  INFO(summary(result.report));
  CHECK(!result.report.converged);
  CHECK(result.report.pair_contacts == 1);
  CHECK(result.report.stuck_contacts == 1);
  CHECK(result.report.stop_reason == "only stuck or abandoned contacts left");
  CHECK(result.report.iterations < options.max_iterations);
  CHECK(brute::changed_vertices(crowd, result.crowd, {0, 19}) == 0);
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
  options.push_size = PushSize::fraction;  // 10 % steps: many iterations
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

TEST_CASE("a trajectory pinned inside an obstacle is left there, not dragged away (real data: agents in pillars)") {
  // Agent 0 stands inside a post at its pinned first and last frames and walks through it in between; agent 1
  // walks past. The contacts at the pinned frames cannot be cleared; the rest must be, without drift.
  CrowdMotion crowd = CrowdMotion::with_shape(28, 2, 0.25);
  for (std::size_t f = 0; f < 28; ++f) {
    crowd.times[f] = 0.4 * static_cast<double>(f);
    crowd.position(f, 0) = Eigen::Vector3d(0.02 * static_cast<double>(f), 0.0, 0.0);
    crowd.position(f, 1) = Eigen::Vector3d(-3.0 + 0.2 * static_cast<double>(f), 2.0, 0.0);
  }
  const std::vector<Obstacle> post{{Circle{{0.27, 0.0}, 0.6}, {}, "pillar"}};
  const Result result = resolve_collisions(crowd, post, unlimited(), quiet);
  INFO(summary(result.report));
  CHECK(!result.report.converged);
  CHECK(result.report.stop_reason == "only stuck or abandoned contacts left");
  CHECK(result.report.iterations < 100);
  CHECK(result.report.stuck_contacts == result.report.remaining());
  CHECK(result.report.obstacle_contacts == 1);
  // Nothing moves further than out of the post (radius + clearance + a push) from where it was.
  CHECK(result.report.max_displacement <= 0.6 + 0.25 + 0.1 + 0.3);
  CHECK(brute::changed_vertices(crowd, result.crowd, {0, 27}) == 0);
  // Only the intervals touching the pinned frames are still inside.
  CrowdMotion inner = result.crowd;
  for (std::size_t f : {0u, 1u, 26u, 27u}) inner.position(f, 0) = Eigen::Vector3d::Constant(std::nan(""));
  CHECK(brute::min_obstacle_slack(inner, post, 0.0) >= -1e-9);
  // With the limits (the pedestrian barely moves: 0.05 m/s, the other walks at 0.5 m/s), stepping 0.85 m out
  // of the post and back is beyond them: the contact is left and reported, and nothing is forced.
  const Result limited = resolve_collisions(crowd, post, Options{}, quiet);
  INFO(summary(limited.report));
  CHECK(!limited.report.converged);
  CHECK(limited.report.stuck_contacts + limited.report.abandoned_contacts == limited.report.remaining());
  CHECK(plausibility(crowd, limited.crowd).empty());
}

TEST_CASE("extreme spreads solve exactly, with and without pinned ends") {
  const auto scene = scenes::bump(3, 481);
  for (double spread : {1.0, 300.0, 1000.0, 1e4, 1e6}) {
    for (bool pins : {true, false}) {
      INFO("spread " << spread << (pins ? " pinned" : " free"));
      Options options = unlimited();
      options.smoothing_time = 0;  // the frame-based energy, where `spread` acts
      options.spread = spread;
      options.pin_ends = pins;
      options.max_iterations = 60;
      Result result;
      REQUIRE_NOTHROW(result = resolve_collisions(scene.crowd, {}, options, quiet));
      INFO(summary(result.report));
      CHECK(result.report.iterations > 0);
      CHECK(std::all_of(result.crowd.positions.begin(), result.crowd.positions.end(), [](double v) { return std::isfinite(v); }));
      // Bounded: no push is ever more than a tenth of a clearance, and no spread lets the pushes start a drift
      // (measured 0.23 m at most; the cap max_displacement, 10 m, would hide one by abandoning contacts).
      CHECK(result.report.max_displacement <= 1.0);
      CHECK(result.report.abandoned_contacts == 0);
      if (pins) CHECK(brute::changed_vertices(scene.crowd, result.crowd, ends(scene.crowd)) == 0);
    }
  }
}

TEST_CASE("the elimination, Schur and linalg (CHOLMOD) track solvers give the same deformation") {
  const auto scene = scenes::bump(3, 120);
  Options options;
  options.max_iterations = 1;
  const Result eliminate = resolve_collisions(scene.crowd, {}, options, quiet);
  REQUIRE(eliminate.report.iterations == 1);
  REQUIRE(eliminate.report.constraints > 5);
  double moved = 0.0;
  for (std::size_t k = 0; k < scene.crowd.positions.size(); ++k) {
    moved = std::max(moved, std::abs(eliminate.crowd.positions[k] - scene.crowd.positions[k]));
  }
  CHECK(moved > 1e-3);
  // All three meet the same pushes exactly on the same system (the minimiser is unique): they differ by
  // rounding only, far below the 1e-3 m the pushes move points.
  for (TrackMethod method : {TrackMethod::schur, TrackMethod::linalg}) {
    options.track_method = method;
    const Result other = resolve_collisions(scene.crowd, {}, options, quiet);
    double apart = 0.0;
    for (std::size_t k = 0; k < scene.crowd.positions.size(); ++k) {
      apart = std::max(apart, std::abs(eliminate.crowd.positions[k] - other.crowd.positions[k]));
    }
    INFO((method == TrackMethod::schur ? "schur" : "linalg") << ": " << apart << " m apart");
    CHECK(apart <= 1e-9);
  }
}

TEST_CASE("the report gives the true smallest clearance, not only below the margin") {
  scenes::CollideScene scene = scenes::bump(2, 90);
  scene.obstacles.push_back({Circle{{0.0, 4.0}, 0.5}, {}, "post"});
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, Options{}, quiet);
  require_clean(scene, result, 0.0);
  // Brute force (fine sampling): sampled values are upper bounds of the exact ones, close for 64 samples.
  const double pair = brute::min_pair_slack(result.crowd, 0.0, 64);
  const double obstacle = brute::min_obstacle_slack(result.crowd, scene.obstacles, 0.0, 64);
  REQUIRE(std::isfinite(result.report.min_pair_gap));
  REQUIRE(std::isfinite(result.report.min_obstacle_gap));
  CHECK(result.report.min_pair_gap <= pair + 1e-12);
  CHECK(result.report.min_pair_gap >= pair - 1e-3);
  CHECK(result.report.min_obstacle_gap <= obstacle + 1e-12);
  CHECK(result.report.min_obstacle_gap >= obstacle - 1e-3);
  CHECK(result.report.min_obstacle_gap > 1.0);  // the post is far from every path: exact beyond the margin too
}

TEST_CASE("repaired motion stays within the limits of walking people, judged by the independent checker") {
  // Speed ≤ 1.25 × the input's fastest, acceleration ≤ 8 m/s² and its 99th percentile ≤ 3 m/s² (or the
  // input's own), on the paper's two scenes, repaired collision-free. The frame-based energy without the
  // limits (the earlier method) broke them: measured 4× the speed on the bump, 11× through the opening.
  const auto bump = scenes::bump(3, 120);
  const Result b = resolve_collisions(bump.crowd, {}, Options{}, quiet);
  require_clean(bump, b, 0.0);
  CHECK(plausibility(bump.crowd, b.crowd).empty());

  const auto opening = scenes::narrow_opening(19, 2.4, 300);
  const Result o = resolve_collisions(opening.crowd, opening.obstacles, Options{}, quiet);
  require_clean(opening, o, 0.0);
  CHECK(plausibility(opening.crowd, o.crowd).empty());

  Options earlier = unlimited();
  earlier.smoothing_time = 0;
  earlier.push_size = PushSize::fraction;
  earlier.obstacle_pull = ObstaclePull::sideways;
  const Result old = resolve_collisions(opening.crowd, opening.obstacles, earlier, quiet);
  REQUIRE(old.report.converged);
  CHECK_FALSE(plausibility(opening.crowd, old.crowd).empty());
}

TEST_CASE("a hopeless pull stops for lack of progress, well before the cap") {
  // Pulling to the nearest boundary point sends trajectories that cross a long wall back and forth across it.
  const auto scene = scenes::narrow_opening(19, 2.4, 300);
  Options options;
  options.obstacle_pull = ObstaclePull::nearest;
  options.contact_patience = 100;
  options.stall_iterations = 500;
  const Result result = resolve_collisions(scene.crowd, scene.obstacles, options, quiet);
  INFO(summary(result.report));
  REQUIRE_FALSE(result.report.converged);
  CHECK(result.report.iterations < options.max_iterations / 10);
  CHECK((result.report.stop_reason == "no progress" || result.report.stop_reason == "only stuck or abandoned contacts left"));
}
