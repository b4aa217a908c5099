// Facing and actions through a collision repair: a repaired agent keeps its facing at the same angle to its
// (repaired) path as in the input; agents the repair does not move keep theirs bit for bit.
#include "scenes.h"

#include <throng/collide/collide.h>
#include <throng/core/progress.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "facing_angles.h"

using namespace throng;
using namespace throng::collide;
using Catch::Matchers::WithinAbs;

TEST_CASE("collide keeps each repaired agent's facing at its angle to the path") {
  // Two groups bumping into each other (paper Figure 8), every agent facing 60° right of its path.
  scenes::CollideScene scene = scenes::bump(3, 120);
  const double angle = -std::numbers::pi / 3;
  test::face_at_angle_to_path(scene.crowd, angle);
  NoProgress quiet;
  const Result result = resolve_collisions(scene.crowd, {}, Options{}, quiet);
  REQUIRE(result.report.moved_agents > 5);
  const CrowdMotion& out = result.crowd;
  REQUIRE(out.orientations.size() == scene.crowd.orientations.size());
  out.validate("repaired");
  std::size_t compared = 0, turned = 0;
  for (std::size_t f = 0; f < out.frame_count(); ++f) {
    for (std::size_t a = 0; a < out.agent_count(); ++a) {
      const auto after = test::facing_to_path(out, f, a);
      if (!after || !test::facing_to_path(scene.crowd, f, a)) continue;
      REQUIRE_THAT(*after, WithinAbs(angle, 1e-9));
      ++compared;
      const double turn = std::abs(test::wrapped(test::facing_yaw(out, f, a) - test::facing_yaw(scene.crowd, f, a)));
      if (turn > 5.0 * std::numbers::pi / 180) ++turned;  // the sidestep turned the facing with the path
    }
  }
  CHECK(compared > out.frame_count() * out.agent_count() / 2);
  CHECK(turned > 50);
  // An agent the repair did not move keeps its input facing and actions exactly.
  for (std::size_t a = 0; a < out.agent_count(); ++a) {
    bool moved = false;
    for (std::size_t f = 0; f < out.frame_count() && !moved; ++f) moved = out.position(f, a) != scene.crowd.position(f, a);
    if (moved) continue;
    for (std::size_t f = 0; f < out.frame_count(); ++f) {
      CHECK(out.orientation(f, a).coeffs() == scene.crowd.orientation(f, a).coeffs());
      CHECK(out.action(f, a) == scene.crowd.action(f, a));
    }
  }
}

TEST_CASE("collide writes no facing for an input without") {
  const scenes::CollideScene scene = scenes::bump(2, 90);
  NoProgress quiet;
  const Result result = resolve_collisions(scene.crowd, {}, Options{}, quiet);
  REQUIRE(result.report.moved_agents > 0);
  CHECK(result.crowd.orientations.empty());
  CHECK(result.crowd.actions.empty());
}
