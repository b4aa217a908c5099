// The facings a crowd carries, as the checker's yaw series (motion_check.h).
#include <throng/check/motion_check.h>

#include <cmath>
#include <limits>

namespace throng::check {

std::optional<FacingSeries> facings_of(const CrowdMotion& crowd) {
  if (crowd.orientations.empty()) return std::nullopt;
  const std::size_t frames = crowd.frame_count(), agents = crowd.agent_count();
  FacingSeries f;
  f.yaw.assign(frames * agents, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t t = 0; t < frames; ++t) {
    for (std::size_t a = 0; a < agents; ++a) {
      if (!crowd.present(t, a)) continue;
      const Eigen::Vector3d forward = crowd.orientation(t, a) * Eigen::Vector3d::UnitX();
      f.yaw[t * agents + a] = std::atan2(forward.y(), forward.x());
    }
  }
  return f;
}

}  // namespace throng::check
