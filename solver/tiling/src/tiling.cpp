#include <throng/tiling/tiling.h>

#include "geometry.h"

namespace throng::tiling {

Eigen::Vector2d Transform::apply(const Eigen::Vector2d& p) const { return rotate(p, angle) + translation; }

Eigen::Vector3d periods(const Region& region) {
  return {region.periodic[0] ? region.max.x() - region.min.x() : 0.0,
          region.periodic[1] ? region.max.y() - region.min.y() : 0.0, region.periodic[2] ? region.t1 - region.t0 : 0.0};
}

bool end_needs_no_partner(const Environment& environment, const Eigen::Vector2d& position, double time, bool is_exit) {
  if (environment.scene.region) {
    const Region& r = *environment.scene.region;
    const auto outside = [](double v, double lo, double hi) { return !(v > lo && v < hi); };
    if (!r.periodic[0] && outside(position.x(), r.min.x(), r.max.x())) return true;
    if (!r.periodic[1] && outside(position.y(), r.min.y(), r.max.y())) return true;
    if (!r.periodic[2] && outside(time, r.t0, r.t1)) return true;
  }
  for (const Zone& z : is_exit ? environment.sinks : environment.sources) {
    if (z.contains(position, time)) return true;
  }
  return false;
}

}  // namespace throng::tiling
