// Obstacles: circles, convex polygons and thick wall segments, static or moving along pose keyframes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <variant>
#include <vector>

namespace throng {

/// A disc: centre and radius (metres).
struct Circle {
  Eigen::Vector2d center{0, 0};
  double radius = 0.5;
};

/// A convex polygon, vertices counter-clockwise (metres). At least 3 vertices.
struct ConvexPolygon {
  std::vector<Eigen::Vector2d> vertices;
};

/// A wall: the segment a–b thickened by `thickness` (metres, total width; the ends are rounded, a capsule).
/// thickness = 0 is an ideal segment.
struct Wall {
  Eigen::Vector2d a{0, 0};
  Eigen::Vector2d b{1, 0};
  double thickness = 0.0;
};

using Shape = std::variant<Circle, ConvexPolygon, Wall>;

/// A rigid pose at a time: the shape's local coordinates are rotated by `angle` (radians, CCW) then translated.
struct PoseKey {
  double time = 0.0;
  Eigen::Vector2d translation{0, 0};
  double angle = 0.0;
};

/// An obstacle: a shape given in its own frame, and its motion. Empty `motion`: static, the shape's
/// coordinates are world coordinates. Otherwise the pose is interpolated linearly between keys (angle too)
/// and held constant before the first and after the last key. Keys have strictly increasing times.
struct Obstacle {
  Shape shape;
  std::vector<PoseKey> motion;
  std::string name;  ///< optional, for messages and pictures

  [[nodiscard]] bool is_moving() const noexcept { return !motion.empty(); }
};

/// The pose (rotation, translation) of an obstacle at time `time`; identity for a static obstacle.
[[nodiscard]] Eigen::Isometry2d pose_at(const Obstacle& obstacle, double time);

/// Where a point is relative to an obstacle.
struct ObstacleDistance {
  double signed_distance = 0.0;  ///< metres from the boundary: negative inside, positive outside
  Eigen::Vector2d nearest{0, 0};  ///< nearest boundary point
  Eigen::Vector2d normal{1, 0};   ///< unit outward normal at `nearest` (from the obstacle toward outside)
};

/// Signed distance from `point` to the obstacle at time `time`, with the nearest boundary point.
[[nodiscard]] ObstacleDistance distance_to(const Obstacle& obstacle, const Eigen::Vector2d& point, double time);

/// Axis-aligned bounds of the obstacle at time `time`.
[[nodiscard]] Eigen::AlignedBox2d bounds_at(const Obstacle& obstacle, double time);

/// Axis-aligned bounds covering every pose over [t0, t1] (exact for static obstacles, conservative for moving).
[[nodiscard]] Eigen::AlignedBox2d bounds_over(const Obstacle& obstacle, double t0, double t1);

/// Moves an obstacle rigidly in the world: a static shape's points go through `motion` (a rotation keeps a
/// polygon counter-clockwise); a moving obstacle's poses become motion ∘ pose (translation ↦ motion · translation,
/// angle ↦ angle + rotation), its key times unchanged. `rotation` is the motion's angle (radians), given so that
/// angles add exactly.
void move_rigidly(Obstacle& obstacle, const Eigen::Isometry2d& motion, double rotation);

/// Checks the shape and motion (radius > 0, polygon convex and CCW with ≥ 3 vertices, finite values, key times
/// increasing); throws InputError naming `what` and the problem.
void validate(const Obstacle& obstacle, const std::string& what);

}  // namespace throng
