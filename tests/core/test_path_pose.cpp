// Facing and action in the data model: the invariants validate() enforces and the default derived from the path
// (the standing rule) that exporters use for crowds that carry no facing.
#include <throng/core/crowd_motion.h>
#include <throng/core/errors.h>

#include <catch2/catch.hpp>

#include <cmath>

using namespace throng;

namespace {

constexpr double pi = 3.14159265358979323846;

// The world direction of the body's forward axis (+x) under q.
Eigen::Vector3d forward(const Eigen::Quaterniond& q) { return q * Eigen::Vector3d::UnitX(); }

// One agent sampled every 0.1 s along `path(t)`.
template <class Path>
CrowdMotion one_agent(std::size_t frames, Path path) {
  CrowdMotion m = CrowdMotion::with_shape(frames, 1);
  for (std::size_t t = 0; t < frames; ++t) {
    m.times[t] = 0.1 * static_cast<double>(t);
    m.position(t, 0) = path(m.times[t]);
  }
  return m;
}

}  // namespace

TEST_CASE("facing_along turns +x onto the direction, without roll") {
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0.3, 0), Eigen::Vector3d(0, -2, 0),
                                  Eigen::Vector3d(3, 4, 5), Eigen::Vector3d(-0.2, 0.1, -1)}) {
    const Eigen::Quaterniond q = facing_along(d);
    INFO("direction " << d.transpose());
    CHECK(std::abs(q.norm() - 1) < 1e-15);
    CHECK((forward(q) - d.normalized()).norm() < 1e-14);
    // No roll: the body's left axis stays horizontal.
    CHECK(std::abs((q * Eigen::Vector3d::UnitY()).z()) < 1e-14);
  }
  CHECK(facing_along(Eigen::Vector3d::Zero()).isApprox(Eigen::Quaterniond::Identity()));
  // A ground-plane direction is a pure yaw: w = cos(yaw/2), z = sin(yaw/2).
  const Eigen::Quaterniond q = facing_along(Eigen::Vector3d(std::cos(2.0), std::sin(2.0), 0));
  CHECK(std::abs(q.w() - std::cos(1.0)) < 1e-15);
  CHECK(std::abs(q.z() - std::sin(1.0)) < 1e-15);
  CHECK(q.x() == 0);
  CHECK(q.y() == 0);
}

TEST_CASE("a walking agent faces along its path, a standing agent keeps its last facing") {
  // East at 1.2 m/s for 1 s, stands 1 s, north at 1.2 m/s for 1 s.
  const CrowdMotion m = one_agent(31, [](double t) {
    if (t <= 1.0 + 1e-9) return Eigen::Vector3d(1.2 * t, 0, 0);
    if (t <= 2.0 + 1e-9) return Eigen::Vector3d(1.2, 0, 0);
    return Eigen::Vector3d(1.2, 1.2 * (t - 2.0), 0);
  });
  PathFacing facing(m);
  const Eigen::Vector3d east(1, 0, 0), north(0, 1, 0);
  for (std::size_t t = 0; t < 31; ++t) {
    const Eigen::Quaterniond q = facing.at(t, 0);
    INFO("frame " << t);
    // Frames 11..19 stand (central differences 0); frames 10 and 20 straddle a stop (0.6 m/s): walking.
    if (t <= 19) CHECK((forward(q) - east).norm() < 1e-12);
    if (t >= 20) CHECK((forward(q) - north).norm() < 1e-12);
    CHECK(path_action(m, t, 0) == (t >= 11 && t <= 19 ? action_stand : action_walk));
  }
}

TEST_CASE("an agent standing at the start faces where it first walks, one that never moves faces +x") {
  const double heading = 2.5;
  const Eigen::Vector3d dir(std::cos(heading), std::sin(heading), 0);
  CrowdMotion m = one_agent(20, [&](double t) { return t < 1.0 - 1e-9 ? Eigen::Vector3d(3, 4, 0) : Eigen::Vector3d(Eigen::Vector3d(3, 4, 0) + 1.4 * (t - 1.0) * dir); });
  PathFacing facing(m);
  for (std::size_t t = 0; t < 20; ++t) CHECK((forward(facing.at(t, 0)) - dir).norm() < 1e-12);

  const CrowdMotion still = one_agent(5, [](double) { return Eigen::Vector3d(1, 1, 0); });
  PathFacing still_facing(still);
  for (std::size_t t = 0; t < 5; ++t) CHECK(still_facing.at(t, 0).isApprox(Eigen::Quaterniond::Identity(), 0));
}

TEST_CASE("jitter below the standing speed does not turn a standing agent") {
  const PathPoseRule rule;
  // Walks east, then stands with ±1 cm jitter every frame (0.1 s): at most 0.2 m/s, below the standing speed.
  const CrowdMotion m = one_agent(30, [](double t) {
    if (t <= 1.0 + 1e-9) return Eigen::Vector3d(t, 0, 0);
    const int k = static_cast<int>(std::lround(t * 10));
    return Eigen::Vector3d(1.0 + (k % 2 ? 0.01 : -0.01), (k % 3 ? 0.01 : -0.01), 0);
  });
  PathFacing facing(m, rule);
  Eigen::Quaterniond last_walking = Eigen::Quaterniond::Identity();
  for (std::size_t t = 0; t <= 10; ++t) last_walking = facing.at(t, 0);
  REQUIRE(path_velocity(m, 10, 0)->norm() >= rule.standing_speed);
  for (std::size_t t = 11; t < 30; ++t) {
    REQUIRE(path_velocity(m, t, 0)->norm() < rule.standing_speed);
    CHECK(facing.at(t, 0).coeffs() == last_walking.coeffs());
  }
}

TEST_CASE("the derived facing of a climbing flyer pitches with its path") {
  const double climb = pi / 6;
  const CrowdMotion m = one_agent(10, [&](double t) { return Eigen::Vector3d(50 * std::cos(climb) * t, 0, 50 * std::sin(climb) * t); });
  PathFacing facing(m);
  for (std::size_t t = 0; t < 10; ++t) {
    const Eigen::Quaterniond q = facing.at(t, 0);
    CHECK((forward(q) - Eigen::Vector3d(std::cos(climb), 0, std::sin(climb))).norm() < 1e-12);
    CHECK(path_action(m, t, 0) == action_run);  // 50 m/s: the speed rule knows no aircraft
  }
}

TEST_CASE("PathFacing gives the same facings in any query order") {
  // Three agents on curving paths with a stop, one absent for a while.
  CrowdMotion m = CrowdMotion::with_shape(40, 3);
  for (std::size_t t = 0; t < 40; ++t) {
    m.times[t] = 0.04 * static_cast<double>(t) + 0.001 * static_cast<double>(t % 3);  // not uniform
    for (std::size_t n = 0; n < 3; ++n) {
      if (n == 2 && t >= 10 && t < 20) continue;
      const double s = t > 15 && t < 25 ? 0.6 : m.times[t];
      m.position(t, n) = Eigen::Vector3d(std::cos(s * (n + 1)) * 3, std::sin(s * (n + 1)) * 3, 0);
    }
  }
  PathFacing in_order(m);
  std::vector<Eigen::Quaterniond> expected;
  for (std::size_t t = 0; t < 40; ++t) {
    for (std::size_t n = 0; n < 3; ++n) expected.push_back(in_order.at(t, n));
  }
  PathFacing backwards(m);
  for (std::size_t i = expected.size(); i-- > 0;) {
    const Eigen::Quaterniond q = backwards.at(i / 3, i % 3);
    CHECK(q.coeffs() == expected[i].coeffs());
  }
  // An agent absent for a while keeps the facing it had when it left.
  CHECK(expected[3 * 15 + 2].coeffs() == expected[3 * 9 + 2].coeffs());
}

TEST_CASE("validate rejects broken orientations and actions with a message naming them") {
  CrowdMotion good = CrowdMotion::with_shape(2, 2);
  good.position(0, 0).setZero();
  good.position(1, 0) = Eigen::Vector3d(1, 0, 0);
  good.orientations.assign(2 * 2 * 4, absent);
  good.orientation(0, 0) = Eigen::Quaterniond::Identity();
  good.orientation(1, 0) = facing_along(Eigen::Vector3d(1, 1, 0));
  good.actions.assign(2 * 2, -1);
  good.action(0, 0) = action_walk;
  good.action(1, 0) = action_stand;
  good.action_table = standard_actions();
  REQUIRE_NOTHROW(good.validate());

  SECTION("orientation size") {
    auto m = good;
    m.orientations.pop_back();
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("expected frames × agents × 4"));
  }
  SECTION("not a unit quaternion") {
    auto m = good;
    m.orientation(1, 0).coeffs() *= 1.01;
    CHECK_THROWS_WITH(m.validate("x"), Catch::Contains("agent 0 at frame 1") && Catch::Contains("unit quaternion"));
  }
  SECTION("NaN orientation of a present agent") {
    auto m = good;
    m.orientation(0, 0).coeffs()[0] = absent;
    CHECK_THROWS_AS(m.validate(), InputError);
  }
  SECTION("action outside the table") {
    auto m = good;
    m.action(1, 0) = 3;
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("has action 3, expected 0..2"));
  }
  SECTION("actions without a table") {
    auto m = good;
    m.action_table.clear();
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("without an action_table"));
  }
  SECTION("repeated table entry") {
    auto m = good;
    m.action_table.push_back({"walk", ""});
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("repeats an earlier entry"));
  }
  SECTION("empty name") {
    auto m = good;
    m.action_table.push_back({"", "umbrella"});
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("empty name"));
  }
  SECTION("a label with a prop is a distinct entry") {
    auto m = good;
    m.action_table.push_back({"walk", "umbrella"});
    CHECK_NOTHROW(m.validate());
  }
}
