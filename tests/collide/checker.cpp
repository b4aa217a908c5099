#include "checker.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace throng::collide::check {
namespace {

bool segment(const CrowdMotion& c, std::size_t f, std::size_t a) { return c.present(f, a) && c.present(f + 1, a); }

Eigen::Vector2d at(const CrowdMotion& c, std::size_t f, std::size_t a, double s) {
  return (1.0 - s) * c.position(f, a).head<2>() + s * c.position(f + 1, a).head<2>();
}

}  // namespace

double min_pair_slack(const CrowdMotion& crowd, double margin, int samples) {
  double slack = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f + 1 < crowd.frame_count(); ++f) {
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      if (!segment(crowd, f, a)) continue;
      for (std::size_t b = a + 1; b < crowd.agent_count(); ++b) {
        if (!segment(crowd, f, b)) continue;
        const double need = crowd.radii[a] + crowd.radii[b] + margin;
        for (int k = 0; k <= samples; ++k) {
          const double s = static_cast<double>(k) / samples;
          slack = std::min(slack, (at(crowd, f, a, s) - at(crowd, f, b, s)).norm() - need);
        }
      }
    }
  }
  return slack;
}

double min_obstacle_slack(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, double margin, int samples) {
  double slack = std::numeric_limits<double>::infinity();
  for (const Obstacle& o : obstacles) {
    for (std::size_t f = 0; f + 1 < crowd.frame_count(); ++f) {
      for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
        if (!segment(crowd, f, a)) continue;
        for (int k = 0; k <= samples; ++k) {
          const double s = static_cast<double>(k) / samples;
          const double t = (1.0 - s) * crowd.times[f] + s * crowd.times[f + 1];
          slack = std::min(slack, distance_to(o, at(crowd, f, a, s), t).signed_distance - crowd.radii[a] - margin);
        }
      }
    }
  }
  return slack;
}

std::size_t changed_vertices(const CrowdMotion& before, const CrowdMotion& after, const std::vector<std::size_t>& frames,
                             const std::vector<char>& agents) {
  std::vector<std::size_t> all = frames;
  if (all.empty()) {
    for (std::size_t f = 0; f < before.frame_count(); ++f) all.push_back(f);
  }
  std::size_t changed = 0;
  for (std::size_t f : all) {
    for (std::size_t a = 0; a < before.agent_count(); ++a) {
      if (!agents.empty() && agents[a] == 0) continue;
      const auto p = before.position(f, a), q = after.position(f, a);
      const bool same = (p.x() == q.x() || (std::isnan(p.x()) && std::isnan(q.x()))) &&
                        (p.y() == q.y() || (std::isnan(p.y()) && std::isnan(q.y())));
      changed += !same;
    }
  }
  return changed;
}

}  // namespace throng::collide::check
