// The motion checker on hand-made paths whose measures are known in closed form: each path breaks exactly one
// limit of the defaults (walking people) once, so the verdict must name that limit and no other.
#include "check_throws.h"

#include <throng/check/motion_check.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>

using namespace throng;
using check::Limits;
using check::Settings;

namespace {

constexpr double dt = 0.1;      // 10 frames per second
constexpr std::size_t T = 201;  // 20 s
constexpr double walk = 1.2;    // m/s

// Two agents, 10 m apart, walking +x at 1.2 m/s: nothing to find.
CrowdMotion straight_walkers() {
  CrowdMotion c = CrowdMotion::with_shape(T, 2, 0.25);
  for (std::size_t f = 0; f < T; ++f) {
    c.times[f] = dt * static_cast<double>(f);
    for (std::size_t a = 0; a < 2; ++a) c.position(f, a) = Eigen::Vector3d(walk * c.times[f], 10.0 * static_cast<double>(a), 0);
  }
  return c;
}

// Agent 0 follows the velocity velocity(f) over interval f (from (0, 0)); agent 1 stays a straight walker.
CrowdMotion with_velocities(const std::function<Eigen::Vector2d(std::size_t)>& velocity) {
  CrowdMotion c = straight_walkers();
  Eigen::Vector2d p(0, 0);
  for (std::size_t f = 0; f < T; ++f) {
    c.position(f, 0) = Eigen::Vector3d(p.x(), p.y(), 0);
    p += dt * velocity(f);
  }
  return c;
}

// The limits the verdict broke, in order.
std::vector<std::string> broken(const check::Statistics& s, const Limits& limits = {}) {
  std::vector<std::string> names;
  for (const check::Violation& v : check::check(s, limits).violations) names.push_back(v.limit);
  return names;
}

check::Statistics measure(const CrowdMotion& c, const std::vector<Obstacle>& obstacles = {},
                          const CrowdMotion* reference = nullptr, const check::FacingSeries* facing = nullptr) {
  return check::measure(c, obstacles, Settings{}, reference, facing);
}

using Names = std::vector<std::string>;

}  // namespace

TEST_CASE("straight walkers break nothing and are measured exactly") {
  const check::Statistics s = measure(straight_walkers());
  CHECK(broken(s).empty());
  CHECK(s.speed.samples == 2 * (T - 1));
  CHECK(s.speed.max == Approx(walk).epsilon(1e-12));
  CHECK(s.speed.p50 == Approx(walk).epsilon(1e-12));
  CHECK(s.acceleration.samples == 2 * (T - 2));
  CHECK(s.acceleration.max < 1e-9);
  CHECK(s.turning_rate.max < 1e-9);
  CHECK(s.contacts.pairs == 0);
  CHECK(s.agent_maxima.size() == 2);
}

TEST_CASE("a speed above the limit, reached gently, breaks max_speed only") {
  // Ramps from 1.2 to 2.8 m/s at 2 m/s² (8 frames), holds, ramps back: speed 2.8 > 2.5, accelerations 2 ≤ 3.
  auto speed = [](std::size_t f) {
    const double t = dt * static_cast<double>(f);
    return walk + std::clamp(std::min(2.0 * (t - 5.0), 2.0 * (12.0 - t)), 0.0, 1.6);
  };
  const check::Statistics s = measure(with_velocities([&](std::size_t f) { return Eigen::Vector2d(speed(f), 0); }));
  CHECK(s.speed.max == Approx(2.8).epsilon(1e-9));
  CHECK(s.speed.max_agent == 0);
  CHECK(s.acceleration.max == Approx(2.0).epsilon(1e-9));
  CHECK(broken(s) == Names{"max_speed"});
  const check::Verdict v = check::check(s, Limits{});
  CHECK(v.violations.front().count == 1);
  CHECK(v.violations.front().bound == 2.5);
}

TEST_CASE("one sudden slow-down breaks max_acceleration only") {
  // 1.2 → 0.3 m/s between two intervals: |Δv| / dt = 9 m/s² > 8 at one frame of 398 (the 99th percentile is 0).
  const check::Statistics s = measure(with_velocities([](std::size_t f) { return Eigen::Vector2d(f < 100 ? walk : 0.3, 0); }));
  CHECK(s.acceleration.max == Approx(9.0).epsilon(1e-9));
  CHECK(s.tangential_acceleration.max == Approx(9.0).epsilon(1e-9));
  CHECK(s.normal_acceleration.max < 1e-9);
  CHECK(s.acceleration.max_time == Approx(10.0));
  CHECK(s.acceleration.p99 < 1e-9);
  CHECK(broken(s) == Names{"max_acceleration"});
}

TEST_CASE("a surging gait breaks acceleration_p99 only") {
  // Six intervals at 1.6 m/s among 1.2 m/s ones: 12 frames at 4 m/s² (3 < 4 < 8). 398 samples: the 99th
  // percentile is the 5th largest, 4.
  const check::Statistics s = measure(with_velocities([](std::size_t f) {
    return Eigen::Vector2d(f >= 50 && f < 62 && f % 2 == 1 ? 1.6 : walk, 0);
  }));
  CHECK(s.acceleration.max == Approx(4.0).epsilon(1e-9));
  CHECK(s.acceleration.p99 == Approx(4.0).epsilon(1e-9));
  CHECK(broken(s) == Names{"acceleration_p99"});
}

TEST_CASE("one sharp turn breaks max_turning_rate only, a weave turning_rate_p99 only") {
  SECTION("a 0.7 rad turn in one frame at 0.6 m/s: 7 rad/s > 2π, 4.1 m/s² < 8") {
    const check::Statistics s = measure(with_velocities([](std::size_t f) {
      return Eigen::Vector2d(0.6 * (f < 100 ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(std::cos(0.7), std::sin(0.7))));
    }));
    CHECK(s.turning_rate.max == Approx(7.0).epsilon(1e-9));
    CHECK(s.acceleration.max == Approx(2 * 0.6 * std::sin(0.35) / dt).epsilon(1e-9));
    CHECK(broken(s) == Names{"max_turning_rate"});
  }
  SECTION("±0.2 rad about +x at 0.6 m/s: 4 rad/s at 20 frames > π, 2.4 m/s² < 3") {
    const check::Statistics s = measure(with_velocities([](std::size_t f) {
      const double heading = f >= 80 && f <= 100 ? (f % 2 == 0 ? 0.2 : -0.2) : 0.0;
      return Eigen::Vector2d(0.6 * std::cos(heading), 0.6 * std::sin(heading));
    }));
    CHECK(s.turning_rate.max == Approx(4.0).epsilon(1e-9));
    CHECK(s.turning_rate.p99 == Approx(4.0).epsilon(1e-9));
    CHECK(s.acceleration.max < 3.0);
    CHECK(broken(s) == Names{"turning_rate_p99"});
  }
}

TEST_CASE("turning is not measured below heading_min_speed") {
  // Reversing at 0.2 m/s (a person shuffling on the spot): no walking direction, no turning sample.
  const check::Statistics s = measure(with_velocities([](std::size_t f) { return Eigen::Vector2d(f % 2 ? 0.2 : -0.2, 0); }));
  CHECK(s.turning_rate.samples == T - 2);  // agent 1's only
  CHECK(s.turning_rate.max < 1e-9);
}

TEST_CASE("a facing that snaps round breaks max_facing_rate only") {
  const CrowdMotion c = straight_walkers();
  check::FacingSeries facing{std::vector<double>(T * 2, 0.0)};
  for (std::size_t f = 120; f < T; ++f) facing.yaw[f * 2] = 1.0;  // +1 rad between frames 119 and 120: 10 rad/s
  facing.yaw[150 * 2 + 1] = std::nan("");                            // unknown at one frame: skipped
  const check::Statistics s = measure(c, {}, nullptr, &facing);
  CHECK(s.has_facing);
  CHECK(s.facing_rate.max == Approx(10.0).epsilon(1e-9));
  CHECK(s.facing_rate.samples == 2 * (T - 1) - 2);
  CHECK(broken(s) == Names{"max_facing_rate"});
  SECTION("angles wrap: −3.1 to +3.1 rad is a turn of 2π − 6.2") {
    check::FacingSeries wrap{std::vector<double>(T * 2, -3.1)};
    for (std::size_t f = 100; f < T; ++f) wrap.yaw[f * 2] = 3.1;
    CHECK(measure(c, {}, nullptr, &wrap).facing_rate.max == Approx((2 * std::numbers::pi - 6.2) / dt).epsilon(1e-9));
  }
  const check::FacingSeries short_series{std::vector<double>(3)};
  CHECK_THROWS_AS(measure(c, {}, nullptr, &short_series), InputError);
}

TEST_CASE("a crowd's own orientations are its facings: the yaw of the forward axis, none where absent") {
  CrowdMotion c = straight_walkers();
  CHECK_FALSE(check::facings_of(c).has_value());
  c.orientations.assign(T * 2 * 4, 0.0);
  for (std::size_t f = 0; f < T; ++f) {
    for (std::size_t a = 0; a < 2; ++a) {
      // Agent 0 turns about +z at 0.2 rad per frame (2 rad/s), agent 1 faces along −y (yaw −π/2).
      const double yaw = a == 0 ? 0.2 * static_cast<double>(f) : -std::numbers::pi / 2;
      c.orientation(f, a) = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    }
  }
  c.position(7, 1) = Eigen::Vector3d::Constant(std::nan(""));  // agent 1 absent at frame 7
  const std::optional<check::FacingSeries> facing = check::facings_of(c);
  REQUIRE(facing.has_value());
  REQUIRE(facing->yaw.size() == T * 2);
  CHECK(facing->yaw[3 * 2] == Approx(0.6).epsilon(1e-12));
  CHECK(facing->yaw[3 * 2 + 1] == Approx(-std::numbers::pi / 2).epsilon(1e-12));
  CHECK(std::isnan(facing->yaw[7 * 2 + 1]));
  // Through measure: the turn of agent 0 is its facing rate (wrapped across ±π).
  CHECK(measure(c, {}, nullptr, &*facing).facing_rate.max == Approx(0.2 / dt).epsilon(1e-9));
}

TEST_CASE("a detour from the reference breaks max_displacement only") {
  const CrowdMotion reference = straight_walkers();
  CrowdMotion c = reference;
  for (std::size_t f = 0; f < T; ++f) {  // a 2.5 m bulge over 20 s: gentle
    const double s = std::sin(std::numbers::pi * static_cast<double>(f) / (T - 1));
    c.position(f, 0).y() += 2.5 * s * s;
  }
  Limits limits;
  limits.max_displacement = 2.0;
  const check::Statistics s = measure(c, {}, &reference);
  CHECK(s.displacement.max == Approx(2.5).epsilon(1e-9));
  CHECK(s.displacement.max_time == Approx(10.0));
  CHECK(s.reference_unmatched == 0);
  CHECK(broken(s, limits) == Names{"max_displacement"});
  CHECK(broken(s).empty());  // unlimited by default
}

TEST_CASE("displacement matches agents by id and interpolates the reference in time") {
  const CrowdMotion reference = straight_walkers();
  CrowdMotion c = CrowdMotion::with_shape(3, 2, 0.25);
  c.ids = {1, 77};  // 77 is not in the reference
  c.times = {0.05, 1.05, 2.0};
  for (std::size_t f = 0; f < 3; ++f) {
    c.position(f, 0) = Eigen::Vector3d(walk * c.times[f], 10.0 + 0.5, 0);  // the reference's agent 1, 0.5 m aside
    c.position(f, 1) = Eigen::Vector3d(0, 0, 0);
  }
  const check::Statistics s = measure(c, {}, &reference);
  CHECK(s.reference_unmatched == 1);
  CHECK(s.displacement.samples == 3);
  CHECK(s.displacement.max == Approx(0.5).epsilon(1e-9));
}

TEST_CASE("two agents brushing past each other break max_pair_contacts only, found between frames") {
  // Two frames 1 s apart: a walks +x, b −x, 0.3 m apart across; at both frames they are 2.03 m apart, at 0.5 s
  // 0.3 m (< 0.5 clearance): one contact, 0.2 m deep.
  CrowdMotion c = CrowdMotion::with_shape(2, 2, 0.25);
  c.times = {0, 1};
  c.position(0, 0) = Eigen::Vector3d(-1, 0, 0);
  c.position(1, 0) = Eigen::Vector3d(1, 0, 0);
  c.position(0, 1) = Eigen::Vector3d(1, 0.3, 0);
  c.position(1, 1) = Eigen::Vector3d(-1, 0.3, 0);
  const check::Statistics s = measure(c);
  CHECK(s.contacts.pairs == 1);
  CHECK(s.contacts.deepest_pair == Approx(0.2).epsilon(1e-9));
  Limits limits;
  limits.max_pair_contacts = 0;
  limits.max_speed = check::unlimited;  // 2 m/s is fine here anyway
  CHECK(broken(s, limits) == Names{"max_pair_contacts"});
  limits.max_pair_contacts = 1;
  CHECK(broken(s, limits).empty());
  SECTION("a margin widens the clearance; a tolerance ignores rounding") {
    Settings wide;
    wide.margin = 1.0;
    c.position(0, 1).y() = c.position(1, 1).y() = 1.4;  // 1.4 m apart at the closest: in contact only with the margin
    CHECK(check::measure(c, {}, Settings{}).contacts.pairs == 0);
    CHECK(check::measure(c, {}, wide).contacts.pairs == 1);
    c.position(0, 1).y() = c.position(1, 1).y() = 0.4995;
    CHECK(check::measure(c, {}, Settings{}).contacts.pairs == 0);
  }
}

TEST_CASE("an agent walking through a pillar breaks max_obstacle_contacts only") {
  const CrowdMotion c = straight_walkers();
  // The pillar's centre is 0.1 m off agent 0's line, level with its frame 83 (x = 9.96 m).
  const std::vector<Obstacle> obstacles{Obstacle{Circle{{9.96, 0.1}, 0.5}, {}, "pillar"},
                                        Obstacle{Circle{{5.0, 5.0}, 0.5}, {}, "clear"}};
  const check::Statistics s = measure(c, obstacles);
  CHECK(s.contacts.obstacle == 1);
  CHECK(s.contacts.deepest_obstacle == Approx(0.25 + 0.5 - 0.1).margin(1e-9));
  Limits limits;
  limits.max_obstacle_contacts = 0;
  CHECK(broken(s, limits) == Names{"max_obstacle_contacts"});
}

TEST_CASE("frames where an agent appears or vanishes carry no acceleration, and nothing spans a gap") {
  CrowdMotion c = straight_walkers();
  for (std::size_t f = 100; f < 110; ++f) c.position(f, 0) = Eigen::Vector3d::Constant(absent);
  for (std::size_t f = 110; f < T; ++f) c.position(f, 0).y() += 50.0;  // reappears 50 m away: no jump measured
  const check::Statistics s = measure(c);
  CHECK(broken(s).empty());
  CHECK(s.speed.samples == (T - 1) + (100 - 1) + (T - 110 - 1));
  CHECK(s.acceleration.samples == (T - 2) + (100 - 2) + (T - 110 - 2));
  SECTION("edge_frames leaves more out at each end of a run") {
    Settings s2;
    s2.edge_frames = 3;
    const check::Statistics e = check::measure(c, {}, s2);
    CHECK(e.speed.samples == (T - 7) + (100 - 7) + (T - 110 - 7));
  }
}

TEST_CASE("limits from a reference: speed by ratio, others never below the input's own") {
  const check::Statistics input = measure(with_velocities([](std::size_t f) { return Eigen::Vector2d(f < 100 ? walk : 0.3, 0); }));
  const Limits l = check::limits_from_reference(input, Limits{}, 1.25);
  CHECK(l.max_speed == Approx(1.25 * walk));
  CHECK(l.max_acceleration == Approx(9.0));         // the input's own 9 m/s²
  CHECK(l.acceleration_p99 == Limits{}.acceleration_p99);
  CHECK(l.max_pair_contacts == std::optional<std::size_t>(0));
  CHECK(broken(input, l).empty());
}

TEST_CASE("the measures do not depend on the thread count") {
  CrowdMotion c = with_velocities([](std::size_t f) { return Eigen::Vector2d(walk * std::cos(0.05 * f), std::sin(0.11 * f)); });
  check::Statistics one, two;
  {
    const ThreadLimit limit(1);
    one = measure(c);
  }
  {
    const ThreadLimit limit(2);
    two = measure(c);
  }
  CHECK(one.acceleration.p99 == two.acceleration.p99);
  CHECK(one.turning_rate.max == two.turning_rate.max);
  CHECK(one.speed.p95 == two.speed.p95);
}

TEST_CASE("bad settings and limits are refused, naming them") {
  Settings s;
  s.obstacle_samples = 0;
  CHECK_THROWS_AS_WITH(check::measure(straight_walkers(), {}, s), ConfigError, Catch::Contains("obstacle_samples"));
  Limits l;
  l.max_speed = 0;
  CHECK_THROWS_AS_WITH(check::check(check::Statistics{}, l), ConfigError, Catch::Contains("max_speed"));
  CrowdMotion bad = straight_walkers();
  bad.times[3] = bad.times[2];
  CHECK_THROWS_AS(check::measure(bad, {}, Settings{}), InputError);
}
