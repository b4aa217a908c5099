// Facing against path, for the tests of the methods that carry facing (edit, collide, stitch, transform).
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/facing_carry.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace throng::test {

/// x wrapped to (−π, π].
inline double wrapped(double x) {
  x = std::remainder(x, 2 * std::numbers::pi);
  return x <= -std::numbers::pi ? x + 2 * std::numbers::pi : x;
}

/// Yaw (radians) of agent a's facing at frame f: where its forward axis (+x) points in the ground plane.
inline double facing_yaw(const CrowdMotion& m, std::size_t f, std::size_t a) {
  const Eigen::Vector3d forward = m.orientation(f, a) * Eigen::Vector3d::UnitX();
  return std::atan2(forward.y(), forward.x());
}

/// The angle from agent a's path tangent to its facing at frame f, where it moves at least `moving` m/s.
inline std::optional<double> facing_to_path(const CrowdMotion& m, std::size_t f, std::size_t a, double moving = 0.3) {
  const auto v = path_velocity(m, f, a);
  if (!v || v->head<2>().norm() < moving) return std::nullopt;
  return wrapped(facing_yaw(m, f, a) - std::atan2(v->y(), v->x()));
}

/// Gives `crowd` orientations at `angle` radians (counter-clockwise) from its path (the default facing turned),
/// and the default actions.
inline void face_at_angle_to_path(CrowdMotion& crowd, double angle) {
  crowd.orientations.clear();
  crowd.actions.clear();
  derive_path_pose(crowd);
  for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      if (crowd.present(f, a)) crowd.orientation(f, a) = turned_by_yaw(crowd.orientation(f, a), angle);
    }
  }
}

}  // namespace throng::test
