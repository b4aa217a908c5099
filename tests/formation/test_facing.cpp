// Facing and action of a formation's individuals (step 13 of formation.h): the direction of travel with the
// standing rule, facings given at keyframes (held there exactly, turned along the shorter arc between them),
// a plane's pitch and bank along its path in 3-D, unit quaternions, the same bits on any thread count.
#include <throng/formation/formation.h>

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>

#include "fixtures.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace throng;
using namespace throng::formation;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;

// A marching block: rows × columns, `spacing` apart, in the xy plane.
Eigen::MatrixXd block(int rows, int columns, double spacing) {
  Eigen::MatrixXd p(rows * columns, 2);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) p.row(r * columns + c) << c * spacing, r * spacing;
  return p;
}

Eigen::MatrixXd shifted(const Eigen::MatrixXd& p, const Eigen::RowVectorXd& by) { return p.rowwise() + by; }

Eigen::Quaterniond yaw_facing(double yaw) { return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())); }

std::vector<Eigen::Quaterniond> everyone(Eigen::Index n, double yaw) {
  return std::vector<Eigen::Quaterniond>(static_cast<std::size_t>(n), yaw_facing(yaw));
}

double yaw_of(const CrowdMotion& m, std::size_t f, std::size_t n) {
  const Eigen::Vector3d forward = m.orientation(f, n) * Eigen::Vector3d::UnitX();
  return std::atan2(forward.y(), forward.x());
}

double angle_between(double a, double b) { return std::remainder(a - b, 2.0 * pi); }

// Every present orientation a unit quaternion (to rounding), every action in the table; validate() agrees.
void require_unit_facings(const CrowdMotion& m) {
  REQUIRE_NOTHROW(m.validate("formation"));
  REQUIRE(m.orientations.size() == m.frame_count() * m.agent_count() * 4);
  REQUIRE(m.actions.size() == m.frame_count() * m.agent_count());
  REQUIRE(m.action_table == standard_actions());
  for (std::size_t f = 0; f < m.frame_count(); ++f)
    for (std::size_t n = 0; n < m.agent_count(); ++n) REQUIRE(std::abs(m.orientation(f, n).norm() - 1.0) < 1e-12);
}

}  // namespace

TEST_CASE("individuals face their direction of travel and keep their facing while they stand") {
  // A block walks 3 m along (4, 3) in 3 s, then stands 3 s. Tension 0: each interval is its own two-keyframe
  // path, so the block starts and stops at rest and stands exactly still in the second interval.
  const Eigen::MatrixXd start = block(3, 4, 1.5);
  const Eigen::RowVector2d travel(2.4, 1.8);
  Problem p;
  p.keyframes.push_back(Keyframe{0.0, start, {}});
  p.keyframes.push_back(Keyframe{3.0, shifted(start, travel), {}});
  p.keyframes.push_back(Keyframe{6.0, shifted(start, travel), {}});
  Options o;
  o.tension = 0.0;
  o.frame_rate_hz = 20;
  const Result r = animate_formation(p, o);
  const CrowdMotion& m = r.motion;
  require_unit_facings(m);
  const double heading = std::atan2(travel.y(), travel.x());
  std::size_t standing = 0;
  for (std::size_t n = 0; n < m.agent_count(); ++n) {
    for (std::size_t f = 0; f < m.frame_count(); ++f) {
      INFO("individual " << n << " frame " << f);
      // Along the travel throughout: while walking it faces the way it goes; before it sets off it faces where
      // it will go, after it stops where it went.
      CHECK(std::abs(angle_between(yaw_of(m, f, n), heading)) < 1e-9);
      CHECK(m.orientation(f, n).x() == 0.0);
      CHECK(m.orientation(f, n).y() == 0.0);
      // A standing individual's facing does not change, to the bit.
      if (f > 0 && m.action(f, n) == action_stand) {
        ++standing;
        CHECK(m.orientation(f, n).coeffs() == m.orientation(f - 1, n).coeffs());
      }
    }
    // Walking in the middle of the move (1.5 m/s at its peak), standing through the second interval.
    CHECK(m.action(30, n) == action_walk);
    for (std::size_t f = 70; f < m.frame_count(); ++f) CHECK(m.action(f, n) == action_stand);
  }
  CHECK(standing > 0);
}

TEST_CASE("an individual whose path reverses turns about at most max_turn_rate, not in one frame") {
  // A block walks 4 m along +x in 4 s and back in 4 s (tension 0: it stops at the middle keyframe).
  const Eigen::MatrixXd start = block(2, 2, 1.5);
  Problem p;
  p.keyframes.push_back(Keyframe{0.0, start, {}});
  p.keyframes.push_back(Keyframe{4.0, shifted(start, Eigen::RowVector2d(4, 0)), {}});
  p.keyframes.push_back(Keyframe{8.0, start, {}});
  Options o;
  o.tension = 0.0;
  o.frame_rate_hz = 25;
  auto largest_turn = [&](const CrowdMotion& m) {
    double most = 0;
    for (std::size_t n = 0; n < m.agent_count(); ++n)
      for (std::size_t f = 1; f < m.frame_count(); ++f)
        most = std::max(most, std::abs(angle_between(yaw_of(m, f, n), yaw_of(m, f - 1, n))) / (m.times[f] - m.times[f - 1]));
    return most;
  };
  SECTION("the default: half a turn per second, and it ends facing back along -x") {
    const CrowdMotion m = animate_formation(p, o).motion;
    require_unit_facings(m);
    CHECK(largest_turn(m) <= pi + 1e-9);
    CHECK(largest_turn(m) > 0.9 * pi);  // it does turn, at the limit
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      CHECK(std::abs(yaw_of(m, 25, n)) < 1e-9);                              // 1 s: walking out along +x
      CHECK(std::abs(angle_between(yaw_of(m, 175, n), pi)) < 1e-9);         // 7 s: walking back along -x
    }
  }
  SECTION("a higher limit turns faster: the travel facing flips within a frame without one") {
    o.facing.max_turn_rate_rad_s = 1e6;
    const CrowdMotion m = animate_formation(p, o).motion;
    CHECK(largest_turn(m) > 25 * pi * 0.99);
  }
}

TEST_CASE("a marching band faces the audience while it walks sideways") {
  // The block marches 6 m along +x over 8 s, facing +y (the audience) at every keyframe.
  const Eigen::MatrixXd start = block(3, 4, 1.5);
  Problem p;
  for (int k = 0; k < 3; ++k) {
    Keyframe key{4.0 * k, shifted(start, Eigen::RowVector2d(3.0 * k, 0.0)), {}};
    key.facings = everyone(start.rows(), 90 * deg);
    p.keyframes.push_back(std::move(key));
  }
  Options o;
  o.frame_rate_hz = 10;
  const Result r = animate_formation(p, o);
  const CrowdMotion& m = r.motion;
  require_unit_facings(m);
  for (std::size_t n = 0; n < m.agent_count(); ++n) {
    for (std::size_t k = 0; k < 3; ++k) {
      // Hit exactly at the keyframe.
      CHECK(m.orientation(r.keyframe_frames[k], n).coeffs() == p.keyframes[k].facings[n].normalized().coeffs());
    }
    for (std::size_t f = 0; f < m.frame_count(); ++f) CHECK(std::abs(angle_between(yaw_of(m, f, n), 90 * deg)) < 1e-12);
    // Sideways indeed: in the middle it moves along +x, across its facing.
    const Eigen::Vector3d v = m.position(41, n) - m.position(39, n);
    CHECK(v.x() > 0.1);  // 0.75 m/s on average: 0.15 m in these 0.2 s
    CHECK(std::abs(v.normalized().dot(m.orientation(40, n) * Eigen::Vector3d::UnitX())) < 1e-9);
  }
}

TEST_CASE("keyframe facings turn along the shorter arc, linearly in time, and hand over to the travel facing") {
  const Eigen::MatrixXd start = block(2, 3, 1.5);
  Options o;
  o.frame_rate_hz = 10;
  SECTION("170° to −170° through 180°, not through 0°") {
    Problem p;
    p.keyframes.push_back(Keyframe{0.0, start, {}});
    p.keyframes.push_back(Keyframe{2.0, shifted(start, Eigen::RowVector2d(2.0, 0.0)), {}});
    p.keyframes[0].facings = everyone(start.rows(), 170 * deg);
    p.keyframes[1].facings = everyone(start.rows(), -170 * deg);
    const Result r = animate_formation(p, o);
    const CrowdMotion& m = r.motion;
    require_unit_facings(m);
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      CHECK(m.orientation(0, n).coeffs() == p.keyframes[0].facings[n].normalized().coeffs());
      CHECK(m.orientation(20, n).coeffs() == p.keyframes[1].facings[n].normalized().coeffs());
      for (std::size_t f = 0; f <= 20; ++f) {
        const double u = m.times[f] / 2.0;
        CHECK(std::abs(angle_between(yaw_of(m, f, n), 170 * deg + u * 20 * deg)) < 1e-9);
      }
    }
  }
  SECTION("a keyframe without facings: from the given facing to the direction of travel") {
    Problem p;
    for (int k = 0; k < 3; ++k) p.keyframes.push_back(Keyframe{2.0 * k, shifted(start, Eigen::RowVector2d(2.0 * k, 0.0)), {}});
    p.keyframes[0].facings = everyone(start.rows(), 90 * deg);
    const Result r = animate_formation(p, o);
    const CrowdMotion& m = r.motion;
    require_unit_facings(m);
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      CHECK(m.orientation(0, n).coeffs() == p.keyframes[0].facings[n].normalized().coeffs());
      for (std::size_t f = 0; f <= 20; ++f) {
        const double u = m.times[f] / 2.0;  // travel along +x: yaw 0
        CHECK(std::abs(angle_between(yaw_of(m, f, n), (1.0 - u) * 90 * deg)) < 1e-6);
      }
      for (std::size_t f = 20; f < m.frame_count(); ++f) CHECK(std::abs(yaw_of(m, f, n)) < 1e-6);
    }
  }
}

TEST_CASE("keyframe facings follow the individuals when rows are matched") {
  // Keyframe 1 lists the individuals in reverse order; its facings are listed with its rows.
  const Eigen::MatrixXd start = block(2, 3, 1.5);
  Problem p;
  p.keyframes.push_back(Keyframe{0.0, start, {}});
  const Eigen::MatrixXd end = shifted(start, Eigen::RowVector2d(3.0, 0.0));
  p.keyframes.push_back(Keyframe{3.0, end.colwise().reverse(), {}});
  for (Eigen::Index i = 0; i < start.rows(); ++i) p.keyframes[1].facings.push_back(yaw_facing(0.1 * static_cast<double>(i)));
  Options o;
  o.match_individuals = true;
  const Result r = animate_formation(p, o);
  require_unit_facings(r.motion);
  const std::size_t last = r.keyframe_frames[1];
  for (std::size_t i = 0; i < r.motion.agent_count(); ++i) {
    const auto row = static_cast<std::size_t>(r.correspondence[1][i]);
    CHECK(r.motion.orientation(last, i).coeffs() == p.keyframes[1].facings[row].normalized().coeffs());
  }
}

TEST_CASE("a plane pitches with its climb and banks into its turn") {
  // Four planes in a diamond (non-coplanar: the 3-D graph needs a volume).
  Eigen::MatrixXd diamond(4, 3);
  diamond << 0, 0, 0, -8, 6, 1, -8, -6, -1, -16, 0, 2;
  Options o;
  o.frame_rate_hz = 20;
  SECTION("a straight climb: nose along the path, wings level") {
    Problem p;
    p.keyframes.push_back(Keyframe{0.0, diamond, {}});
    p.keyframes.push_back(Keyframe{3.0, shifted(diamond, Eigen::RowVector3d(90.0, 0.0, 30.0)), {}});
    const Result r = animate_formation(p, o);
    const CrowdMotion& m = r.motion;
    require_unit_facings(m);
    const Eigen::Vector3d along = Eigen::Vector3d(90, 0, 30).normalized();
    for (std::size_t n = 0; n < 4; ++n) {
      for (std::size_t f = 0; f < m.frame_count(); ++f) {
        CHECK(((m.orientation(f, n) * Eigen::Vector3d::UnitX()) - along).norm() < 1e-6);
        CHECK(((m.orientation(f, n) * Eigen::Vector3d::UnitY()) - Eigen::Vector3d::UnitY()).norm() < 1e-6);
      }
    }
  }
  SECTION("a level circle: banked toward the centre by the coordinated-turn angle") {
    // Round a circle of 150 m at 30 m/s (the formation turning with it), 16 keyframes a lap: 31.4° of bank.
    const double radius = 150.0, speed = 30.0, height = 500.0;
    const int keys = 16;
    const double lap = 2 * pi * radius / speed;
    Problem p;
    for (int k = 0; k <= keys; ++k) {
      const double theta = 2 * pi * k / keys;
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(theta + 0.5 * pi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::RowVector3d centre(radius * std::cos(theta), radius * std::sin(theta), height);
      p.keyframes.push_back(Keyframe{lap * k / keys, shifted(diamond * turn.transpose(), centre), {}});
    }
    const Result r = animate_formation(p, o);
    const CrowdMotion& m = r.motion;
    require_unit_facings(m);
    // Away from the ends (duplicated endpoints change the spline there): each plane's bank is the coordinated
    // turn's, atan(a_lat / g) for the lateral acceleration of its own path (the spline between keyframes, whose
    // curvature is not quite the circle's), the wing inside the turn low. Measured here over ±1 frame; the
    // facing's 0.5-s window sees the curvature change a little along it.
    const std::size_t from = r.keyframe_frames[2], to = r.keyframe_frames[keys - 2];
    for (std::size_t n = 0; n < 4; ++n) {
      for (std::size_t f = from; f < to; f += 7) {
        INFO("plane " << n << " frame " << f);
        const Eigen::Vector3d at = m.position(f, n);
        const double dt = m.times[f + 1] - m.times[f];
        const Eigen::Vector3d v = (m.position(f + 1, n) - m.position(f - 1, n)) / (2 * dt);
        const Eigen::Vector3d a = (m.position(f + 1, n) - 2 * at + m.position(f - 1, n)) / (dt * dt);
        const Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(v).normalized();
        const double expected = std::atan(a.dot(left) / o.facing.gravity_mps2);
        CHECK(expected > 25 * deg);  // the circle's atan(v² / (R g)) is 31.4°
        const Eigen::Vector3d up = m.orientation(f, n) * Eigen::Vector3d::UnitZ();
        const Eigen::Vector3d inward = -Eigen::Vector3d(at.x(), at.y(), 0).normalized();
        CHECK(up.dot(inward) > 0);
        CHECK(std::abs(std::acos(std::clamp(up.z(), -1.0, 1.0)) - expected) < 0.5 * deg);
        // The nose along the path, nearly level.
        CHECK(std::abs((m.orientation(f, n) * Eigen::Vector3d::UnitX()).z()) < 0.05);
      }
    }
  }
}

TEST_CASE("facings and actions: the same bits on one and two threads, with keyframe facings and collisions") {
  Problem p;
  for (int k = 0; k < 3; ++k)
    p.keyframes.push_back(Keyframe{2.0 * k, throng::test::scattered(200, 10.0, 70 + static_cast<std::uint64_t>(k), 0.8), {}});
  Rng rng(5);
  for (int i = 0; i < 200; ++i) p.keyframes[1].facings.push_back(yaw_facing(rng.uniform(-pi, pi)));
  Options o;
  o.frame_rate_hz = 15;
  o.collision.enabled = true;
  o.collision.min_distance_m = 0.7;
  Result one, two;
  {
    ThreadLimit limit(1);
    one = animate_formation(p, o);
  }
  {
    ThreadLimit limit(2);
    two = animate_formation(p, o);
  }
  require_unit_facings(one.motion);
  CHECK(one.motion.orientations == two.motion.orientations);
  CHECK(one.motion.actions == two.motion.actions);
}

TEST_CASE("keyframe facings of the wrong count or not unit quaternions are refused, naming the keyframe") {
  const Eigen::MatrixXd start = block(2, 2, 1.5);
  Problem p;
  p.keyframes.push_back(Keyframe{0.0, start, {}});
  p.keyframes.push_back(Keyframe{2.0, shifted(start, Eigen::RowVector2d(2.0, 0.0)), {}});
  p.keyframes[1].where = "job.yaml:9:3 (keyframes[1])";
  p.keyframes[1].facings = everyone(3, 0.0);
  CHECK_THROWS_WITH(animate_formation(p, Options{}),
                    Catch::Contains("job.yaml:9:3 (keyframes[1])") && Catch::Contains("3 facings for 4 individuals"));
  p.keyframes[1].facings = everyone(4, 0.0);
  p.keyframes[1].facings[2].coeffs() *= 2.0;
  CHECK_THROWS_AS(animate_formation(p, Options{}), InputError);
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Catch::Contains("individual 2 has facing"));
  p.keyframes[1].facings[2] = Eigen::Quaterniond(std::nan(""), 0, 0, 0);
  CHECK_THROWS_AS(animate_formation(p, Options{}), InputError);
  Options bad;
  bad.facing.smoothing_s = -1;
  p.keyframes[1].facings.clear();
  CHECK_THROWS_AS(animate_formation(p, bad), ConfigError);
}
