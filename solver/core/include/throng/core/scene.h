// Scene: what surrounds the crowd — obstacles and an optional space-time region.
#pragma once

#include <throng/core/obstacle.h>

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace throng {

/// A space-time box [min.x, max.x] × [min.y, max.y] × [t0, t1] with periodic flags per axis (x, y, t).
/// Repeating tiles wrap around the periodic axes; elsewhere the region bounds where a method works.
struct Region {
  Eigen::Vector2d min{0, 0};
  Eigen::Vector2d max{10, 10};
  double t0 = 0.0;
  double t1 = 10.0;
  std::array<bool, 3> periodic{false, false, false};

  [[nodiscard]] bool contains(const Eigen::Vector2d& p, double t) const noexcept {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y() && t >= t0 && t <= t1;
  }
};

struct Scene {
  std::vector<Obstacle> obstacles;
  std::optional<Region> region;

  /// Validates every obstacle and the region; throws InputError naming `what` and the problem.
  void validate(const std::string& what = "scene") const;
};

}  // namespace throng
