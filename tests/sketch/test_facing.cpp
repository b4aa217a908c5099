// Facing and actions from the simulation (sketch.h "Facing and actions"): the walking direction, smoothed and
// turn-rate limited; a standing agent keeps its facing; walk / stand / run from the walking speed.
#include <throng/core/crowd_motion.h>
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "scenes.h"

using namespace throng::sketch;
using Eigen::Vector2d;

namespace {

constexpr double pi = std::numbers::pi;

double wrapped(double x) {
  x = std::remainder(x, 2 * pi);
  return x <= -pi ? x + 2 * pi : x;
}

// Yaw of agent a's facing at frame f (forward axis +x turned into the world).
double yaw(const throng::CrowdMotion& m, std::size_t f, std::size_t a) {
  const Eigen::Vector3d forward = m.orientation(f, a) * Eigen::Vector3d::UnitX();
  return std::atan2(forward.y(), forward.x());
}

// A straight band along `direction` (unit), `length` m long and 2·half_width wide, drawn at `speed` m/s.
Drawing straight_band(const Vector2d& direction, double length, double half_width, double speed) {
  const Vector2d side(-direction.y(), direction.x());
  Drawing d;
  const auto points = static_cast<std::size_t>(length) + 1;
  d.strokes.push_back(scenes::straight_stroke(Vector2d::Zero(), length * direction, points, speed));
  for (const double s : {half_width, -half_width}) {
    d.strokes.push_back(scenes::straight_stroke(s * side, s * side + length * direction, points, speed));
  }
  return d;
}

}  // namespace

TEST_CASE("sketch output carries a unit-quaternion facing and a standard action for every present agent") {
  Options o;
  o.agent_count = 30;
  const SimulationResult r = simulate(straight_band(Vector2d(1, 0), 40, 3, 1.4), {}, o);
  const throng::CrowdMotion& m = r.motion;
  REQUIRE(m.orientations.size() == m.frame_count() * m.agent_count() * 4);
  REQUIRE(m.actions.size() == m.frame_count() * m.agent_count());
  CHECK(m.action_table == throng::standard_actions());
  m.validate("sketch output");  // unit quaternions, actions in the table
}

TEST_CASE("on a straight stroke every walking agent faces the walking direction") {
  // A diagonal course (45°), so that a facing left at the identity (+x) fails. The walking direction: where the
  // agent goes over the half second around the frame (its positions; the facing is not computed from them).
  const Vector2d direction = Vector2d(1, 1).normalized();
  Options o;
  o.agent_count = 40;
  const SimulationResult r = simulate(straight_band(direction, 60, 4, 1.4), {}, o);
  const throng::CrowdMotion& m = r.motion;
  REQUIRE(r.finished);
  std::size_t walking = 0;
  double largest = 0, sum = 0, course_sum = 0;
  const std::size_t k = 6;  // frames each side: ±0.24 s at 25 fps
  for (std::size_t f = k; f + k < m.frame_count(); ++f) {
    if (m.times[f] < 3.0) continue;  // past the start, where agents accelerate and spread
    for (std::size_t a = 0; a < m.agent_count(); ++a) {
      if (!m.present(f, a) || m.action(f, a) != throng::action_walk) continue;
      const Eigen::Vector3d ahead = m.position(f + k, a) - m.position(f - k, a);
      if (ahead.norm() < 0.3 * 2 * k / o.output_rate_hz) continue;  // not walking over the whole window
      const double off = std::abs(wrapped(yaw(m, f, a) - std::atan2(ahead.y(), ahead.x())));
      largest = std::max(largest, off);
      sum += off;
      course_sum += std::abs(wrapped(yaw(m, f, a) - pi / 4));
      ++walking;
    }
  }
  REQUIRE(walking > 40 * 25 * 10);  // 40 agents walking for more than 10 s
  INFO("facing off the walking direction: mean " << sum / walking * 180 / pi << "°, max " << largest * 180 / pi
                                                  << "°; off the course: mean " << course_sum / walking * 180 / pi << "°");
  CHECK(sum / static_cast<double>(walking) < 3.0 * pi / 180);
  CHECK(largest < 20.0 * pi / 180);
  CHECK(course_sum / static_cast<double>(walking) < 5.0 * pi / 180);
}

TEST_CASE("a standing agent's facing does not change") {
  // Agents arrive, stop and stand at the end, making room for late ones, for 20 s after the last arrives.
  Options o;
  o.agent_count = 60;
  o.end_of_path = EndOfPath::stop;
  const Drawing d = straight_band(Vector2d(0, 1), 30, 3, 1.4);
  o.duration_s = 0;
  const double finish = simulate(d, {}, o).motion.times.back();
  o.duration_s = finish + 20;
  const SimulationResult r = simulate(d, {}, o);
  const throng::CrowdMotion& m = r.motion;
  std::size_t standing = 0, arrived_standing = 0;
  double largest_turn = 0;
  for (std::size_t f = 1; f < m.frame_count(); ++f) {
    for (std::size_t a = 0; a < m.agent_count(); ++a) {
      if (!m.present(f, a) || !m.present(f - 1, a) || m.action(f, a) != throng::action_stand) continue;
      // Standing over the interval into frame f: the facing is the one it had.
      // (Up to rounding: a frame can fall a rounding error short of its step's end.)
      largest_turn = std::max(largest_turn, std::abs(wrapped(yaw(m, f, a) - yaw(m, f - 1, a))));
      ++standing;
      if (m.times[f] > r.arrival_time_s[a] + 5.0) ++arrived_standing;
    }
  }
  CHECK(largest_turn < 1e-9);
  CHECK(arrived_standing > 60 * 25 * 10);  // every agent stands for over 10 s at the end
  CHECK(standing >= arrived_standing);
}

TEST_CASE("under avoidance jitter the facing turns no faster than facing_turn_rate_rad_s and is far steadier than the velocity") {
  // The paper's rule (no direction filter) in a dense, narrow band: F swings from step to step and so does the
  // raw velocity; the facing must not.
  Options o;
  o.direction_filter_s = 0;
  o.agent_count = 120;
  o.duration_s = 30;
  const SimulationResult r = simulate(straight_band(Vector2d(1, 0), 80, 2, 1.4), {}, o);
  const throng::CrowdMotion& m = r.motion;
  const double frame_s = 1.0 / o.output_rate_hz;
  double facing_max = 0, facing_sum = 0, raw_max = 0, raw_sum = 0;
  std::size_t count = 0;
  for (std::size_t f = 2; f < m.frame_count(); ++f) {
    for (std::size_t a = 0; a < m.agent_count(); ++a) {
      if (!m.present(f, a) || !m.present(f - 1, a) || !m.present(f - 2, a)) continue;
      const double facing_turn = std::abs(wrapped(yaw(m, f, a) - yaw(m, f - 1, a)));
      facing_max = std::max(facing_max, facing_turn);
      facing_sum += facing_turn;
      const Eigen::Vector3d v1 = m.position(f, a) - m.position(f - 1, a), v0 = m.position(f - 1, a) - m.position(f - 2, a);
      if (v1.norm() < 1e-9 || v0.norm() < 1e-9) continue;
      const double raw_turn = std::abs(wrapped(std::atan2(v1.y(), v1.x()) - std::atan2(v0.y(), v0.x())));
      raw_max = std::max(raw_max, raw_turn);
      raw_sum += raw_turn;
      ++count;
    }
  }
  REQUIRE(count > 50000);
  INFO("facing: max " << facing_max * 180 / pi << "°, mean " << facing_sum / count * 180 / pi << "°; raw velocity: max "
                      << raw_max * 180 / pi << "°, mean " << raw_sum / count * 180 / pi << "° per frame");
  CHECK(raw_max > 90.0 * pi / 180);  // the scene does jitter
  CHECK(facing_max <= facing_turn_rate_rad_s * frame_s * (1 + 1e-9));
  CHECK(facing_sum < 0.25 * raw_sum);
}

TEST_CASE("actions: walk on the slow part, run where the stroke was drawn fast, stand at the end") {
  // 30 m drawn at 1.2 m/s, then 30 m at 3 m/s (above PathPoseRule's 2 m/s).
  const auto centre = [](double s) { return Vector2d(s, 0); };
  const auto speed = [](double s) { return s < 30 ? 1.2 : 3.0; };
  Drawing d;
  for (const double side : {0.0, 3.0, -3.0}) {
    d.strokes.push_back(scenes::drawn_stroke(centre, 60, 1.0, [side](double) { return side; }, speed));
  }
  Options o;
  o.agent_count = 20;
  o.duration_s = simulate(d, {}, o).motion.times.back() + 5;  // 5 s after the last arrival: all have slowed down
  const SimulationResult r = simulate(d, {}, o);
  const throng::CrowdMotion& m = r.motion;
  REQUIRE(r.finished);
  std::size_t walk_slow = 0, slow = 0, run_fast = 0, fast = 0;
  for (std::size_t f = 1; f < m.frame_count(); ++f) {
    for (std::size_t a = 0; a < m.agent_count(); ++a) {
      if (!m.present(f, a)) continue;
      const double x = m.position(f, a).x();
      const double v = (m.position(f, a) - m.position(f - 1, a)).norm() * o.output_rate_hz;
      if (x > 10 && x < 25) {
        ++slow;
        walk_slow += m.action(f, a) == throng::action_walk;
      } else if (x > 40 && x < 55 && v > 2.5) {
        ++fast;
        run_fast += m.action(f, a) == throng::action_run;
      }
    }
  }
  REQUIRE(slow > 1000);
  REQUIRE(fast > 500);
  CHECK(walk_slow > 0.95 * slow);
  CHECK(run_fast > 0.95 * fast);
  const std::size_t last = m.frame_count() - 1;
  for (std::size_t a = 0; a < m.agent_count(); ++a) CHECK(m.action(last, a) == throng::action_stand);
}
