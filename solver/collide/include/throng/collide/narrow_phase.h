// Narrow phase of collision repair (paper §6.1; docs/METHODS.md §1.3): exact tests on one frame
// interval of piecewise-linear trajectories.
//
// Between two frames every agent moves on a straight line at constant speed, so over the interval
// p(s) = (1 − s) p0 + s p1 with s ∈ [0, 1] the fraction of the interval.
//  * Two agents: their offset p_a(s) − p_b(s) is linear in s, its squared length a quadratic; the minimum over
//    [0, 1] is at the clamped vertex of the parabola (closed form).
//  * An agent and an obstacle: the signed distance of a convex shape is a convex function of the point, so along
//    a segment in the obstacle's own frame it is convex in s. Computed exactly for every shape: a circle (closest
//    point of the segment to the centre), a thick wall (segment–segment distance to the wall's core, minus half
//    the thickness), a convex polygon (inside: the minimum of max_k(n_k·p − c_k), a piecewise-linear convex
//    function whose minimum is at an end or where two edge lines cross; outside: segment–edge distances).
//    A moving obstacle is handled in its own frame: the interval is split at the obstacle's pose keys; where its
//    angle is constant the local path is still a segment (exact); where it rotates the local path is a curve,
//    cut into chords finely enough (from a bound on its curvature) that each is within `chord_tolerance` of it,
//    and each chord's minimum is lowered by its error bound: the signed distance is 1-Lipschitz, so the result
//    is never above the true minimum and at most twice the tolerance below it. "No contact" is then a proof of
//    no penetration, for rotating obstacles too.
// Everything is 2-D (x, y); z is ignored.
#pragma once

#include <throng/core/obstacle.h>

#include <Eigen/Core>

namespace throng::collide {

/// Closest approach of two linearly moving points over s ∈ [0, 1].
struct Approach {
  double s = 0.0;         ///< fraction of the interval where the distance is smallest (the earliest if several)
  double distance = 0.0;  ///< metres, the smallest distance
  Eigen::Vector2d offset{0, 0};  ///< p_a(s) − p_b(s) at that moment
};

/// Exact closest approach of a: a0 → a1 and b: b0 → b1 over one interval.
[[nodiscard]] Approach closest_approach(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                                        const Eigen::Vector2d& b1);

/// The deepest point of a segment path relative to an obstacle.
struct Penetration {
  double s = 0.0;                ///< fraction of the interval where the signed distance is smallest
  double signed_distance = 0.0;  ///< metres at that point: negative inside the obstacle
};

/// Minimum over s ∈ [0, 1] of the obstacle's signed distance to p(s) = (1 − s) p0 + s p1 at time
/// t0 + s (t1 − t0). Exact for static and translating obstacles; for rotating ones a lower bound within
/// 2·chord_tolerance metres (see above).
[[nodiscard]] Penetration deepest_penetration(const Obstacle& obstacle, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                                              double t0, double t1, double chord_tolerance = 1e-4);

/// Minimum over s ∈ [0, 1] of the signed distance of a static shape (in its own coordinates) to the segment
/// p0 → p1 (exact).
[[nodiscard]] Penetration deepest_penetration(const Shape& shape, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1);

}  // namespace throng::collide
