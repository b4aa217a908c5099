// Carrying facing and actions through a deformation (throng/core/facing_carry.h).
#include <throng/core/crowd_motion.h>
#include <throng/core/facing_carry.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "facing_angles.h"

using namespace throng;
using Catch::Matchers::WithinAbs;

namespace {

// No turn-rate limit: the carrying rule exactly (the limit has its own test below).
constexpr double exact = std::numeric_limits<double>::infinity();

constexpr double pi = std::numbers::pi;

// One agent: walks east 10 frames at 1 m/s (dt 0.1), stands 10 frames, walks east again 10 frames.
CrowdMotion walk_stand_walk() {
  CrowdMotion c = CrowdMotion::with_shape(30, 1);
  double x = 0;
  for (std::size_t f = 0; f < 30; ++f) {
    c.times[f] = 0.1 * static_cast<double>(f);
    c.position(f, 0) << x, 0, 0;
    if (f < 9 || f >= 19) x += 0.1;
  }
  return c;
}

}  // namespace

TEST_CASE("turned_by_yaw turns about +z and yaw_change measures the turn") {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond r = turned_by_yaw(q, pi / 2);
  const Eigen::Vector3d before = q * Eigen::Vector3d::UnitX(), after = r * Eigen::Vector3d::UnitX();
  CHECK_THAT(after.z(), WithinAbs(before.z(), 1e-12));  // the pitch is kept
  CHECK_THAT(yaw_change(before, after), WithinAbs(pi / 2, 1e-12));
  CHECK_THAT(yaw_change(Eigen::Vector3d(-1, 0.01, 0), Eigen::Vector3d(-1, -0.01, 0)), WithinAbs(0.02, 1e-6));  // across ±π
}

TEST_CASE("a path bent by 90° turns a sideways facing by 90°, standing frames by the nearest moving frame's turn") {
  CrowdMotion before = walk_stand_walk();
  test::face_at_angle_to_path(before, pi / 2);  // facing north while walking east
  // After: the second walk goes north instead of east (the standing frames stay where they were).
  CrowdMotion after = before;
  for (std::size_t f = 19; f < 30; ++f) {
    const double along = before.position(f, 0).x() - before.position(18, 0).x();
    after.position(f, 0) << before.position(18, 0).x(), along, 0;
  }
  carry_facing_same_frames(before, after, {0}, {}, exact);  // the rule alone, not limited
  for (std::size_t f = 0; f < 30; ++f) {
    INFO("frame " << f);
    // Frames 10..18 stand: 10..14 take the first walk's turn (0; 14 is a tie, the earlier wins), 15..18 the
    // second walk's (90°).
    const double expected = f <= 14 ? pi / 2 : pi;
    CHECK_THAT(test::wrapped(test::facing_yaw(after, f, 0) - expected), WithinAbs(0, 1e-9));
  }
  // Wherever the agent moves, facing and path keep their angle.
  for (std::size_t f = 0; f < 30; ++f) {
    if (const auto angle = test::facing_to_path(after, f, 0)) CHECK_THAT(*angle, WithinAbs(pi / 2, 1e-9));
  }
}

TEST_CASE("only the agents asked are carried, and an input without facing gives none") {
  CrowdMotion before = walk_stand_walk();
  CrowdMotion plain = before;
  carry_facing_same_frames(plain, before, {0});
  CHECK(before.orientations.empty());
  CHECK(before.actions.empty());
  test::face_at_angle_to_path(before, 0.7);
  CrowdMotion after = before;
  for (std::size_t f = 0; f < 30; ++f) after.position(f, 0).y() += 0.05 * static_cast<double>(f);
  carry_facing_same_frames(before, after, {});
  CHECK(after.orientations == before.orientations);  // not asked: copied bit for bit
}

TEST_CASE("walk/stand/run follow the new speed where it changed class, other actions pass through") {
  CrowdMotion before = walk_stand_walk();
  test::face_at_angle_to_path(before, 0.0);
  before.action_table.push_back({"wave", "flag"});
  for (std::size_t f = 25; f < 30; ++f) before.action(f, 0) = 3;  // waving while walking
  CrowdMotion after = before;
  // Three times as far per frame in the first walk (3 m/s: run); the second walk is unchanged.
  for (std::size_t f = 0; f < 30; ++f) after.position(f, 0).x() *= f < 10 ? 3.0 : 1.0;
  for (std::size_t f = 10; f < 30; ++f) after.position(f, 0).x() += 2 * 0.9;
  carry_facing_same_frames(before, after, {0}, {}, exact);  // the rule alone, not limited
  CHECK(after.action_table.size() == 4);  // run was in the standard table already
  for (std::size_t f = 1; f < 8; ++f) CHECK(after.action(f, 0) == action_run);
  for (std::size_t f = 11; f < 18; ++f) CHECK(after.action(f, 0) == action_stand);
  for (std::size_t f = 20; f < 25; ++f) CHECK(after.action(f, 0) == action_walk);
  for (std::size_t f = 25; f < 30; ++f) CHECK(after.action(f, 0) == 3);
  after.validate("carried");
}

TEST_CASE("a span with a frame offset, a rigid rotation and an action map") {
  CrowdMotion before = walk_stand_walk();
  test::face_at_angle_to_path(before, pi / 2);
  // After: 40 frames; frames 10..39 are before's 0..29 turned by 90° (a rigid alignment, no deformation).
  CrowdMotion after = CrowdMotion::with_shape(40, 1);
  for (std::size_t f = 0; f < 40; ++f) after.times[f] = 0.1 * static_cast<double>(f);
  for (std::size_t f = 10; f < 40; ++f) {
    const Eigen::Vector3d p = before.position(f - 10, 0);
    after.position(f, 0) << -p.y(), p.x(), 0;
  }
  after.orientations.assign(40 * 4, absent);
  after.actions.assign(40, -1);
  after.action_table = {{"stand", ""}, {"walk", ""}, {"run", ""}};
  const std::vector<std::int32_t> map = merge_action_tables(before.action_table, after.action_table);
  CHECK(map == std::vector<std::int32_t>{1, 0, 2});
  carry_facing(before, after, CarriedSpan{0, 0, 10, 39, -10, pi / 2, &map, exact});
  for (std::size_t f = 10; f < 40; ++f) {
    CHECK_THAT(test::wrapped(test::facing_yaw(after, f, 0) - pi), WithinAbs(0, 1e-9));  // north turned by 90°
    CHECK(after.action_table[static_cast<std::size_t>(after.action(f, 0))] ==
          before.action_table[static_cast<std::size_t>(before.action(f - 10, 0))]);
  }
}

TEST_CASE("carried facings turn at most carried_max_turn_rate: a 90° bend in one frame is turned over a third of a second") {
  CrowdMotion before = walk_stand_walk();
  test::face_at_angle_to_path(before, pi / 2);
  CrowdMotion after = before;
  for (std::size_t f = 19; f < 30; ++f) {
    const double along = before.position(f, 0).x() - before.position(18, 0).x();
    after.position(f, 0) << before.position(18, 0).x(), along, 0;
  }
  CrowdMotion exact_after = after;
  carry_facing_same_frames(before, exact_after, {0}, {}, exact);
  carry_facing_same_frames(before, after, {0});
  double largest = 0, exact_largest = 0;
  for (std::size_t f = 1; f < 30; ++f) {
    const double dt = after.times[f] - after.times[f - 1];
    largest = std::max(largest, after.orientation(f - 1, 0).angularDistance(after.orientation(f, 0)) / dt);
    exact_largest = std::max(exact_largest, exact_after.orientation(f - 1, 0).angularDistance(exact_after.orientation(f, 0)) / dt);
  }
  CHECK(exact_largest > 2 * carried_max_turn_rate);  // the rule alone turns faster than a person
  CHECK(largest <= carried_max_turn_rate * (1 + 1e-9));
  CHECK(largest > 0.99 * carried_max_turn_rate);
  // It catches up: the last frame faces as the rule says.
  CHECK(after.orientation(29, 0).angularDistance(exact_after.orientation(29, 0)) < 1e-9);
}
