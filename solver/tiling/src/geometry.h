// Small geometric helpers of the tiler: angles, periodic images, the closest approach of two moving discs.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace throng::tiling {

/// Wraps an angle to (−π, π].
[[nodiscard]] inline double wrap_angle(double a) noexcept {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

/// 2-D rotation of `p` by `angle`.
[[nodiscard]] inline Eigen::Vector2d rotate(const Eigen::Vector2d& p, double angle) noexcept {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

/// The nearest-image offset along an axis of period `period` (0: not periodic): the multiple k of the period
/// that makes |d − k·period| smallest, for a difference d = a − b.
[[nodiscard]] inline int nearest_image(double d, double period) noexcept {
  return period > 0 ? static_cast<int>(std::lround(d / period)) : 0;
}

/// Periods per axis (x, y, t); 0 on non-periodic axes.
struct Periods {
  std::array<double, 3> p{0, 0, 0};
  [[nodiscard]] bool any() const noexcept { return p[0] > 0 || p[1] > 0 || p[2] > 0; }
};

/// A moving disc over one path segment: centre from a at time ta to b at time tb (tb > ta), linear in between.
struct MovingDisc {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
  double ta;
  double tb;
  double radius;
};

/// Smallest distance between the centres of two moving discs over their common time interval; +∞ when the
/// intervals do not overlap. The relative motion is linear over the common interval, so the minimum is exact.
[[nodiscard]] inline double closest_approach(const MovingDisc& p, const MovingDisc& q) noexcept {
  const double lo = std::max(p.ta, q.ta), hi = std::min(p.tb, q.tb);
  if (lo > hi) return std::numeric_limits<double>::infinity();
  const auto at = [](const MovingDisc& m, double t) {
    const double s = (t - m.ta) / (m.tb - m.ta);
    return Eigen::Vector2d(m.a + s * (m.b - m.a));
  };
  const Eigen::Vector2d d0 = at(p, lo) - at(q, lo);
  if (hi == lo) return d0.norm();
  const Eigen::Vector2d d1 = at(p, hi) - at(q, hi);
  const Eigen::Vector2d w = d1 - d0;
  const double ww = w.squaredNorm();
  const double s = ww > 0 ? std::clamp(-d0.dot(w) / ww, 0.0, 1.0) : 0.0;
  return (d0 + s * w).norm();
}

/// `d` moved by whole periods to its image nearest to `q` (segment midpoints compared on each periodic axis).
[[nodiscard]] inline MovingDisc nearest_image_of(MovingDisc d, const MovingDisc& q, const Periods& periods) noexcept {
  if (!periods.any()) return d;
  const Eigen::Vector2d qm = 0.5 * (q.a + q.b), dm = 0.5 * (d.a + d.b);
  const Eigen::Vector2d shift(nearest_image(qm.x() - dm.x(), periods.p[0]) * periods.p[0],
                              nearest_image(qm.y() - dm.y(), periods.p[1]) * periods.p[1]);
  const double tshift = nearest_image(0.5 * (q.ta + q.tb) - 0.5 * (d.ta + d.tb), periods.p[2]) * periods.p[2];
  d.a += shift;
  d.b += shift;
  d.ta += tshift;
  d.tb += tshift;
  return d;
}

}  // namespace throng::tiling
