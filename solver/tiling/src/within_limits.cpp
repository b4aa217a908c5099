#include "within_limits.h"

#include "geometry.h"

#include <cmath>

namespace throng::tiling {
namespace {

double turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

}  // namespace

bool within_limits(const Fragment& fragment, const Path& path, const DeformationLimits& limits,
                   double max_speed_m_s) noexcept {
  const std::size_t n = fragment.sample_count();
  const std::vector<Eigen::Vector2d>& p = fragment.positions;
  const std::vector<Eigen::Vector2d>& q = path.positions;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double dt = fragment.times[i + 1] - fragment.times[i];
    const double dt_new = path.times[i + 1] - path.times[i];
    if (!(dt_new > 0)) return false;
    const double frames = dt / limits.frame_period_s;
    if (std::abs(dt_new - dt) > limits.time_shift_s * frames) return false;
    const double length = (q[i + 1] - q[i]).norm();
    if (std::abs(length - (p[i + 1] - p[i]).norm()) > limits.stretch_m * frames) return false;
    if (length > max_speed_m_s * dt_new) return false;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Eigen::Vector2d a = p[i] - p[i - 1], b = p[i + 1] - p[i];
    const Eigen::Vector2d a2 = q[i] - q[i - 1], b2 = q[i + 1] - q[i];
    const double m = limits.bend_min_segment_m;
    if (a.norm() <= m || b.norm() <= m || a2.norm() <= m || b2.norm() <= m) continue;
    const double frames = 0.5 * (fragment.times[i + 1] - fragment.times[i - 1]) / limits.frame_period_s;
    if (std::abs(wrap_angle(turn(a2, b2) - turn(a, b))) > limits.bend_rad * frames) return false;
  }
  return true;
}

}  // namespace throng::tiling
