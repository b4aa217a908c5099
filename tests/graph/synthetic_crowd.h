// Synthetic crowds for the graph and edit tests: a grid formation marching along an arc.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/random.h>

#include <Eigen/Geometry>

#include <cmath>

namespace throng::test {

/// rows × cols agents `spacing` metres apart (plus up to `jitter` metres of seeded noise in their places), the
/// formation's rows facing its heading, marching at `speed` m/s for `frames` frames of `dt` s along an arc
/// turning at `turn_rate` rad/s. Agent ids are 100 + index, so ids and indices differ.
inline CrowdMotion marching_grid(int rows, int cols, std::size_t frames, double spacing = 1.0, double speed = 1.2,
                                 double dt = 0.1, double turn_rate = 0.0, double jitter = 0.1, std::uint64_t seed = 5) {
  CrowdMotion crowd = CrowdMotion::with_shape(frames, static_cast<std::size_t>(rows * cols));
  Rng rng(seed);
  std::vector<Eigen::Vector2d> offsets;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      // x along the heading (rows one behind the other), y across.
      offsets.emplace_back(-spacing * r + rng.uniform(-jitter, jitter),
                           spacing * (c - 0.5 * (cols - 1)) + rng.uniform(-jitter, jitter));
    }
  }
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) crowd.ids[a] = 100 + static_cast<std::int64_t>(a);
  Eigen::Vector2d centre(0, 0);
  double heading = 0.0;
  for (std::size_t f = 0; f < frames; ++f) {
    crowd.times[f] = static_cast<double>(f) * dt;
    const Eigen::Rotation2Dd turn(heading);
    for (std::size_t a = 0; a < offsets.size(); ++a) {
      const Eigen::Vector2d p = centre + turn * offsets[a];
      crowd.position(f, a) << p.x(), p.y(), 0.0;
    }
    centre += speed * dt * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    heading += turn_rate * dt;
  }
  return crowd;
}

}  // namespace throng::test
