// Obstacles and the region in a YAML job, shared by every job that has a scene (sketch, collide, tile ...).
//
//   obstacles:
//     - circle: {center: [x, y], radius: r}
//     - polygon: [[x, y], [x, y], [x, y], ...]          # convex; clockwise input is reversed to CCW
//     - wall: {from: [x, y], to: [x, y], thickness: t}  # thickness (m, total width) defaults to 0.2
//       name: north wall                                 # optional, any obstacle
//       motion:                                          # optional: pose keys (moving obstacle)
//         - {time: 0, translation: [0, 0], angle: 0}    # angle in degrees (rotation about the shape's origin)
//         - {time: 5, translation: [4, 0], angle: 90}
//   region: {min: [x, y], max: [x, y], time: [t0, t1], periodic: [false, false, false]}   # optional
#pragma once

#include <throng/core/scene.h>
#include <throng/io/config.h>

namespace throng {

/// Reads the `obstacles` and `region` keys of `job` (both optional) and validates them (ConfigError naming the line).
[[nodiscard]] Scene read_scene(const ConfigNode& job);
/// Reads the `obstacles` key alone (for jobs without a region).
[[nodiscard]] std::vector<Obstacle> read_obstacles(const ConfigNode& job);

/// Writes `scene` as the same keys into `job` (for the effective config).
void write_scene(YAML::Node& job, const Scene& scene);

}  // namespace throng
