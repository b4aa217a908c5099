#include "scenes.h"

#include <throng/core/random.h>

#include <cmath>
#include <numbers>

namespace throng::collide::scenes {
namespace {

constexpr double fps = 30.0;

CrowdMotion shaped(std::size_t frames, std::size_t agents, double radius) {
  CrowdMotion crowd = CrowdMotion::with_shape(frames, agents, radius);
  for (std::size_t f = 0; f < frames; ++f) crowd.times[f] = static_cast<double>(f) / fps;
  return crowd;
}

// Agent `agent` walks from `start` with `velocity` (m/s), z = 0.
void walk(CrowdMotion& crowd, std::size_t agent, const Eigen::Vector2d& start, const Eigen::Vector2d& velocity) {
  for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
    const Eigen::Vector2d p = start + crowd.times[f] * velocity;
    crowd.position(f, agent) = Eigen::Vector3d(p.x(), p.y(), 0.0);
  }
}

Obstacle wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness, const char* name) {
  Obstacle o;
  o.shape = Wall{a, b, thickness};
  o.name = name;
  return o;
}

}  // namespace

CollideScene bump(std::size_t side, std::size_t frames) {
  const double spacing = 1.2, gap = 2.0;
  const double duration = static_cast<double>(frames - 1) / fps;
  const double width = spacing * static_cast<double>(side - 1);
  const double speed = (width + gap) / duration;  // each group ends where the other started
  CollideScene s;
  s.crowd = shaped(frames, 2 * side * side, 0.25);
  std::size_t agent = 0;
  for (int group = 0; group < 2; ++group) {
    const double direction = group == 0 ? 1.0 : -1.0;
    for (std::size_t i = 0; i < side; ++i) {
      for (std::size_t j = 0; j < side; ++j) {
        const double x = -direction * (0.5 * gap + 0.5 * width) - 0.5 * width + spacing * static_cast<double>(i);
        const double y = -0.5 * width + spacing * static_cast<double>(j) + (group == 0 ? 0.0 : 0.1);
        s.crowd.species[agent] = group;
        walk(s.crowd, agent++, {x, y}, {direction * speed, 0.0});
      }
    }
  }
  return s;
}

CollideScene narrow_opening(std::size_t agents, double opening, std::size_t frames) {
  const double speed = 1.3, ring_spacing = 0.8;
  CollideScene s;
  s.crowd = shaped(frames, agents, 0.25);
  const double duration = static_cast<double>(frames - 1) / fps;
  // Rings: 1 agent at the centre, then rings of radius k·0.8 m holding ⌊2πk⌋ agents each.
  std::size_t agent = 0;
  for (int ring = 0; agent < agents; ++ring) {
    const double radius = ring_spacing * ring;
    const std::size_t count = ring == 0 ? 1 : static_cast<std::size_t>(2.0 * std::numbers::pi * ring);
    for (std::size_t k = 0; k < count && agent < agents; ++k) {
      const double angle = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(count) + 0.1 * ring;
      const Eigen::Vector2d offset(radius * std::cos(angle), radius * std::sin(angle));
      walk(s.crowd, agent++, Eigen::Vector2d(0.0, -0.5 * speed * duration) + offset, {0.0, speed});
    }
  }
  s.obstacles.push_back(wall({-40.0, 0.0}, {-0.5 * opening - 0.2, 0.0}, 0.4, "west wall"));
  s.obstacles.push_back(wall({0.5 * opening + 0.2, 0.0}, {40.0, 0.0}, 0.4, "east wall"));
  return s;
}

CollideScene crossing(std::size_t per_group, std::size_t frames) {
  constexpr double crossing_fps = 5.0;
  const double spacing = 1.5, gap = 1.0;
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(per_group))));
  const double width = spacing * static_cast<double>(side - 1);
  const double duration = static_cast<double>(frames - 1) / crossing_fps;
  const double speed = (2.0 * width + 2.0 * gap) / duration;  // from one side of the other group's lane to the other
  CollideScene s;
  s.crowd = shaped(frames, 2 * per_group, 0.25);
  for (std::size_t f = 0; f < frames; ++f) s.crowd.times[f] = static_cast<double>(f) / crossing_fps;
  std::size_t agent = 0;
  for (int group = 0; group < 2; ++group) {
    for (std::size_t k = 0; k < per_group; ++k) {
      const double along = -1.5 * width - gap + spacing * static_cast<double>(k / side);
      const double across = -0.5 * width + spacing * static_cast<double>(k % side) + 0.37 * group;
      s.crowd.species[agent] = group;
      if (group == 0) {
        walk(s.crowd, agent++, {along, across}, {speed, 0.0});
      } else {
        walk(s.crowd, agent++, {across, along}, {0.0, speed});
      }
    }
  }
  return s;
}

CrowdMotion random_crowd(std::size_t agents, std::size_t frames, double extent, double step, std::uint64_t seed) {
  CrowdMotion crowd = shaped(frames, agents, 0.25);
  Rng rng(seed);
  for (std::size_t a = 0; a < agents; ++a) {
    crowd.radii[a] = rng.uniform(0.2, 0.35);
    // A quarter of the agents enter late or leave early.
    std::size_t first = 0, last = frames;
    if (rng.below(4) == 0) first = rng.below(frames / 2);
    if (rng.below(4) == 0) last = frames / 2 + rng.below(frames / 2);
    Eigen::Vector2d p(rng.uniform(0.0, extent), rng.uniform(0.0, extent));
    for (std::size_t f = first; f < last; ++f) {
      crowd.position(f, a) = Eigen::Vector3d(p.x(), p.y(), 0.0);
      p += Eigen::Vector2d(rng.uniform(-step, step), rng.uniform(-step, step));
    }
  }
  return crowd;
}

std::vector<Obstacle> scattered_obstacles() {
  std::vector<Obstacle> out;
  out.push_back({Circle{{5, 5}, 1.5}, {}, "post"});
  out.push_back({ConvexPolygon{{{10, 2}, {13, 2}, {12, 6}}}, {}, "block"});
  out.push_back({Wall{{1, 12}, {14, 13}, 0.3}, {}, "wall"});
  out.push_back({Circle{{0, 0}, 1.0}, {{0.0, {2, 8}, 0.0}, {3.0, {12, 9}, 0.0}}, "moving post"});
  return out;
}

}  // namespace throng::collide::scenes
