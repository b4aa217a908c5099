// Facing and actions through transform and stitch: a rigid transform turns every facing by its rotation; a
// stitched clip keeps each agent's facing at the same angle to its (blended) path as in its clip.
#include "../graph/synthetic_crowd.h"

#include <throng/stitch/stitch.h>
#include <throng/stitch/transform.h>

#include <throng/core/facing_carry.h>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

#include "facing_angles.h"

using namespace throng;
using namespace throng::stitch;
using Catch::Matchers::WithinAbs;

namespace {

constexpr double pi = std::numbers::pi;

// Turns and moves every position of `c` by p ↦ R(angle) p + shift, and shifts its times.
CrowdMotion placed(CrowdMotion c, double angle, const Eigen::Vector2d& shift, double time_shift) {
  const Eigen::Rotation2Dd R(angle);
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    c.times[f] += time_shift;
    for (std::size_t a = 0; a < c.agent_count(); ++a) c.position(f, a).head<2>() = R * Eigen::Vector2d(c.position(f, a).head<2>()) + shift;
  }
  return c;
}

}  // namespace

TEST_CASE("a transform by 90° turns every facing by 90°, keeping a 3-D orientation's pitch") {
  CrowdMotion c = test::marching_grid(2, 3, 21, 1.0, 1.2, 0.1, 0.4, 0.1);
  test::face_at_angle_to_path(c, 0.3);
  // One agent's orientation pitched up (an airshow plane climbing): the turn is about the world's +z.
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    c.orientation(f, 4) = Eigen::Quaterniond(c.orientation(f, 4)) * Eigen::Quaterniond(Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitY()));
  }
  CrowdMotion moved = c;
  Scene scene;
  TransformOptions o;
  o.rotation = pi / 2;
  o.translation = Eigen::Vector2d(5, -3);
  transform(moved, scene, o);
  moved.validate("transformed");
  const Eigen::Matrix3d R = Eigen::AngleAxisd(pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < c.agent_count(); ++a) {
      const Eigen::Vector3d before = c.orientation(f, a) * Eigen::Vector3d::UnitX();
      const Eigen::Vector3d after = moved.orientation(f, a) * Eigen::Vector3d::UnitX();
      REQUIRE((after - R * before).norm() < 1e-12);
      REQUIRE_THAT(test::wrapped(test::facing_yaw(moved, f, a) - test::facing_yaw(c, f, a)), WithinAbs(pi / 2, 1e-12));
      // The up axis too: the whole orientation turned, not only the forward axis.
      REQUIRE(((moved.orientation(f, a) * Eigen::Vector3d::UnitZ()) - R * (c.orientation(f, a) * Eigen::Vector3d::UnitZ())).norm() < 1e-12);
    }
  }
  CHECK(moved.actions == c.actions);  // no retiming: actions unchanged

  SECTION("a retiming that halves the speed turns a run into a walk; other actions stay") {
    CrowdMotion fast = test::marching_grid(1, 2, 21, 1.0, 2.6, 0.1, 0.0, 0.0);
    test::face_at_angle_to_path(fast, 0.0);
    fast.action_table.push_back({"juggle", "balls"});
    for (std::size_t f = 0; f < 21; ++f) fast.action(f, 1) = 3;
    REQUIRE(fast.action(10, 0) == action_run);
    TransformOptions slow;
    slow.time_scale = 2;
    transform(fast, scene, slow);
    for (std::size_t f = 0; f < 21; ++f) {
      CHECK(fast.action(f, 0) == action_walk);
      CHECK(fast.action(f, 1) == 3);
    }
  }
}

TEST_CASE("a stitched clip keeps every agent's facing at its angle to the stitched path") {
  // G faces 90° left of its path (a sideways walk); G′ is another formation placed elsewhere and turned by
  // 120°, facing 90° left of its path too: the alignment turns it back and the blend bends the paths.
  CrowdMotion g = test::marching_grid(3, 4, 31, 1.0, 1.3, 0.1, 0.2, 0.05, 1);
  CrowdMotion g2 = test::marching_grid(3, 4, 41, 1.5, 1.3, 0.1, -0.2, 0.05, 2);
  test::face_at_angle_to_path(g, pi / 2);
  const Eigen::Vector2d end = g.position(30, 0).head<2>();
  g2 = placed(g2, 2.1, end + Eigen::Vector2d(3, 2), 10);
  test::face_at_angle_to_path(g2, pi / 2);
  Options o;
  o.guard.enabled = false;  // the guard's time warp is the time warp's to carry (throng/timewarp)
  const Result r = stitch_clips(g, g2, o);
  const CrowdMotion& out = r.crowd;
  REQUIRE(out.orientations.size() == out.frame_count() * out.agent_count() * 4);
  out.validate("stitched");
  CHECK(std::abs(r.report.rotation) > 1.0);  // the alignment turned G′ back
  std::size_t compared = 0;
  for (std::size_t f = 0; f < out.frame_count(); ++f) {
    for (std::size_t a = 0; a < out.agent_count(); ++a) {
      if (const auto angle = test::facing_to_path(out, f, a)) {
        INFO("frame " << f << " agent " << a);
        REQUIRE_THAT(*angle, WithinAbs(pi / 2, 1e-9));
        ++compared;
      }
    }
  }
  CHECK(compared == out.frame_count() * out.agent_count());

  SECTION("a G′ without facing contributes the path's default: facing along its path after the joint") {
    CrowdMotion plain = g2;
    plain.orientations.clear();
    plain.actions.clear();
    plain.action_table.clear();
    const Result mixed = stitch_clips(g, plain, o);
    const std::size_t J = g.frame_count() - 1;
    const CrowdMotion& m = mixed.crowd;
    // At the joint the facing turns from 90° off the path to along it, no faster than a person turns
    // (carried_max_turn_rate), and holds the rule once it has turned.
    const double settle = m.times[J] + (pi / 2) / carried_max_turn_rate + (m.times[J + 1] - m.times[J]);
    for (std::size_t f = 0; f < m.frame_count(); ++f) {
      for (std::size_t a = 0; a < m.agent_count(); ++a) {
        INFO("frame " << f << " agent " << a);
        const auto angle = test::facing_to_path(m, f, a);
        REQUIRE(angle);
        if (f <= J) REQUIRE_THAT(*angle, WithinAbs(pi / 2, 1e-9));
        else if (m.times[f] >= settle) REQUIRE_THAT(*angle, WithinAbs(0.0, 1e-9));
        if (f > 0) REQUIRE(m.orientation(f - 1, a).angularDistance(m.orientation(f, a)) <=
                           carried_max_turn_rate * (m.times[f] - m.times[f - 1]) * (1 + 1e-9));
      }
    }
  }
  SECTION("clips without facing give a stitched clip without") {
    CrowdMotion a = g, b = g2;
    for (CrowdMotion* c : {&a, &b}) {
      c->orientations.clear();
      c->actions.clear();
      c->action_table.clear();
    }
    const Result none = stitch_clips(a, b, o);
    CHECK(none.crowd.orientations.empty());
    CHECK(none.crowd.actions.empty());
  }
}
