// Facing and action in the data model: the invariants validate() enforces and the default derived from the path
// (the standing rule) that exporters use for crowds that carry no facing.
#include <throng/core/crowd_motion.h>
#include <throng/core/errors.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

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

namespace {

// Runs the same queries through at() agent by agent (the reference) and through at_frame(t, n0, n1); counts the
// coefficients that differ in any bit.
struct FacingPair {
  PathFacing reference, batched;
  std::vector<Eigen::Quaterniond> row;
  std::size_t differ = 0, compared = 0;
  FacingPair(const CrowdMotion& m, const PathPoseRule& rule) : reference(m, rule), batched(m, rule), row(m.agent_count()) {}
  void compare(std::size_t t, std::size_t n0, std::size_t n1) {
    batched.at_frame(t, n0, n1, row.data());
    for (std::size_t n = n0; n < n1; ++n) {
      const Eigen::Vector4d a = reference.at(t, n).coeffs(), b = row[n - n0].coeffs();
      for (int c = 0; c < 4; ++c) differ += std::memcmp(&a[c], &b[c], sizeof(double)) != 0;
      ++compared;
    }
  }
};

std::vector<PathPoseRule> standing_rules() {
  std::vector<PathPoseRule> rules;
  for (const double standing : {0.3, 1e-200, 0.0, -1.0, std::nan("")}) rules.push_back({standing, 2.0});
  return rules;
}

}  // namespace

TEST_CASE("PathFacing::at_frame gives at()'s facings bit for bit, over ranges, in any order") {
  // 150 agents (more than one batch of 64) over 30 frames: walking every way (both half-planes, straight back
  // along −x, standing, slower than the standing speed), absent for a while, present at one frame alone, climbing
  // (a vertical component), crawling at 1e-130 m/s (below facing_along's direct range) and flying at 1e130 m/s
  // (above it); with given velocities of either sign, some vertical, some NaN. Standing speeds 0.3, tiny, 0,
  // negative and NaN. Ranges of odd and even lengths (the two-at-a-time path and its tail), walked frame by frame,
  // backwards, and skipping frames.
  constexpr std::size_t T = 30, N = 150;
  CrowdMotion m = CrowdMotion::with_shape(T, N);
  for (std::size_t t = 0; t < T; ++t) m.times[t] = 0.04 * static_cast<double>(t) + 0.001 * static_cast<double>(t % 4);
  for (std::size_t n = 0; n < N; ++n) {
    const double heading = 2 * pi * static_cast<double>(n) / 37.0 - pi;
    for (std::size_t t = 0; t < T; ++t) {
      if (n % 11 == 3 && t >= 8 && t < 14) continue;       // absent for a while
      if (n % 13 == 5 && t != 12) continue;                // present at one frame alone
      double speed = 0.2 + 0.05 * static_cast<double>(n % 40);  // some below the standing speed
      if (n % 17 == 0 && t > 10 && t < 20) speed = 0;      // stops
      if (n == 7) speed = 1e-130;
      if (n == 8) speed = 1e130;
      const double along = speed * m.times[t];
      const double climb = n % 19 == 4 ? 0.3 * m.times[t] : 0.0;
      const double turn = n % 2 ? 0.4 * m.times[t] : 0.0;
      m.position(t, n) = Eigen::Vector3d(static_cast<double>(n) + along * std::cos(heading + turn), along * std::sin(heading + turn), climb);
    }
  }
  m.position(5, 9) = Eigen::Vector3d(9.0, 0.0, 0.0);  // agent 9 at frame 6 walks straight back along −x
  m.position(6, 9) = Eigen::Vector3d(8.9, 0.0, 0.0);
  m.position(7, 9) = Eigen::Vector3d(8.8, 0.0, 0.0);
  CrowdMotion with_velocities = m;
  with_velocities.velocities.assign(m.positions.size(), 0.0);
  for (std::size_t i = 0; i < with_velocities.velocities.size(); ++i) {
    const double v = (0.05 + 0.01 * static_cast<double>(i % 97)) * (i % 5 < 2 ? -1.0 : 1.0);
    with_velocities.velocities[i] = i % 11 == 0 ? std::nan("") : i % 3 == 2 ? (i % 23 == 2 ? v : 0.0) : v;
  }
  for (const CrowdMotion* motion : {&m, &with_velocities}) {
    for (const PathPoseRule& rule : standing_rules()) {
      INFO((motion == &m ? "from positions" : "given velocities") << ", standing speed " << rule.standing_speed);
      FacingPair frames(*motion, rule), odd(*motion, rule), single(*motion, rule), replayed(*motion, rule);
      for (std::size_t t = 0; t < T; ++t) {
        frames.compare(t, 0, N);    // all agents: two batches of 64 and 22
        odd.compare(t, 0, 67);      // odd lengths: the tail of the two-at-a-time pass
        odd.compare(t, 67, N);
        single.compare(t, 1, 2);    // one agent, continuing its state every frame
      }
      for (std::size_t t = T; t-- > 20;) replayed.compare(t, 30, 101);  // backwards: every value replayed
      for (std::size_t t = 3; t < T; t += 5) replayed.compare(t, 1, 2);   // skipping frames
      for (const FacingPair* pair : {&frames, &odd, &single, &replayed}) CHECK(pair->differ == 0);
      CHECK(frames.compared == T * N);
    }
  }
}

TEST_CASE("PathFacing::at_frame gives at()'s facings bit for bit on random crowds and random queries") {
  // Steps of random size over 280 orders of magnitude and either sign, some exactly zero (±0 differences), climbs
  // that are 0, subnormal (their velocity may underflow to 0) or ordinary; agents absent at random; given
  // velocities the same way with NaNs. Queries: random ranges at frames mostly in order, sometimes going back.
  std::mt19937_64 random(20261207);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto magnitude = [&] { return std::pow(10.0, -140.0 + 280.0 * unit(random)) * (unit(random) < 0.5 ? -1.0 : 1.0); };
  const auto step = [&] {
    const double u = unit(random);
    return u < 0.1 ? 0.0 : u < 0.15 ? -0.0 : u < 0.6 ? (unit(random) - 0.5) : magnitude();
  };
  const auto climb = [&] {
    const double u = unit(random);
    return u < 0.7 ? 0.0 : u < 0.85 ? 5e-324 * std::floor(1 + 3 * unit(random)) : step();
  };
  constexpr std::size_t T = 24, N = 101;
  for (int crowd = 0; crowd < 4; ++crowd) {
    CrowdMotion m = CrowdMotion::with_shape(T, N);
    for (std::size_t t = 0; t < T; ++t) m.times[t] = 0.1 * static_cast<double>(t) + (crowd % 2 ? 1e3 : 0.0);
    for (std::size_t n = 0; n < N; ++n) {
      Eigen::Vector3d p(unit(random), unit(random), 0.0);
      for (std::size_t t = 0; t < T; ++t) {
        p += Eigen::Vector3d(step(), step(), climb());
        if (!p.allFinite()) p = Eigen::Vector3d(unit(random), unit(random), 0.0);
        if (unit(random) < 0.1) continue;  // absent
        m.position(t, n) = p;
      }
    }
    if (crowd >= 2) {
      m.velocities.resize(m.positions.size());
      for (double& v : m.velocities) v = unit(random) < 0.1 ? std::nan("") : unit(random) < 0.3 ? step() : unit(random) < 0.5 ? magnitude() : 0.0;
    }
    for (const PathPoseRule& rule : standing_rules()) {
      INFO("crowd " << crowd << ", standing speed " << rule.standing_speed);
      FacingPair pair(m, rule);
      std::size_t t = 0;
      for (int query = 0; query < 600; ++query) {
        const double u = unit(random);
        t = u < 0.05 ? static_cast<std::size_t>(unit(random) * T) : u < 0.6 ? std::min(T - 1, t + 1) : t;
        const std::size_t n0 = static_cast<std::size_t>(unit(random) * N);
        const std::size_t n1 = std::min(N, n0 + 1 + static_cast<std::size_t>(unit(random) * 80));
        pair.compare(t, n0, n1);
      }
      CHECK(pair.differ == 0);
    }
  }
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
