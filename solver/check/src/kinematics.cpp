#include "kinematics.h"

#include <Eigen/Core>

#include <cmath>
#include <numbers>

namespace throng::check::detail {
namespace {

using Vec = Eigen::Vector3d;

// Angle in (−π, π] equal to `a` modulo 2π.
double wrapped(double a) {
  a = std::remainder(a, 2 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2 * std::numbers::pi : a;
}

}  // namespace

AgentKinematics agent_kinematics(const CrowdMotion& crowd, std::size_t agent, const Settings& settings,
                                 const FacingSeries* facing) {
  AgentKinematics k;
  const std::size_t T = crowd.frame_count(), N = crowd.agent_count(), edge = settings.edge_frames;
  for (std::size_t first = 0; first < T;) {
    if (!crowd.present(first, agent)) {
      ++first;
      continue;
    }
    std::size_t end = first;  // the run is [first, end)
    while (end < T && crowd.present(end, agent)) ++end;
    // Frames [lo, hi) of the run are measured: `edge` more frames are left out at each end.
    const std::size_t lo = first + edge, hi = end > first + 2 * edge ? end - edge : lo;
    auto p = [&](std::size_t f) { return Vec(crowd.position(f, agent)); };
    auto velocity = [&](std::size_t f) { return Vec((p(f + 1) - p(f)) / (crowd.times[f + 1] - crowd.times[f])); };
    for (std::size_t f = lo; f + 1 < hi; ++f) {
      k.speed.add(velocity(f).norm(), agent, crowd.times[f]);
      if (facing != nullptr) {
        const double a = facing->yaw[f * N + agent], b = facing->yaw[(f + 1) * N + agent];
        if (std::isfinite(a) && std::isfinite(b)) {
          k.facing.add(std::abs(wrapped(b - a)) / (crowd.times[f + 1] - crowd.times[f]), agent, crowd.times[f]);
        }
      }
    }
    for (std::size_t f = lo + 1; f + 1 < hi; ++f) {
      const Vec before = velocity(f - 1), after = velocity(f);
      const double h = 0.5 * (crowd.times[f + 1] - crowd.times[f - 1]);
      const Vec a = (after - before) / h;
      const double t = crowd.times[f];
      k.acceleration.add(a.norm(), agent, t);
      const Vec mean = before + after;
      if (mean.norm() > 0) {
        const Vec u = mean.normalized();
        const double along = a.dot(u);
        k.tangential.add(std::abs(along), agent, t);
        k.normal.add((a - along * u).norm(), agent, t);
      }
      if (before.norm() >= settings.heading_min_speed && after.norm() >= settings.heading_min_speed) {
        const double angle = std::atan2(before.cross(after).norm(), before.dot(after));
        k.turning.add(angle / h, agent, t);
      }
    }
    first = end;
  }
  return k;
}

}  // namespace throng::check::detail
