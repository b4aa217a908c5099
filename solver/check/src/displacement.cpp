#include "displacement.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <optional>

namespace throng::check::detail {

AgentIndex index_by_id(const CrowdMotion& crowd) {
  AgentIndex index;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) index.emplace(crowd.ids[a], a);
  return index;
}

namespace {

// The reference agent's position at time t: a frame within `tolerance`, else linear between the two frames
// around t when it is present at both; none otherwise.
std::optional<Eigen::Vector3d> reference_at(const CrowdMotion& reference, std::size_t partner, double t, double tolerance) {
  const std::vector<double>& times = reference.times;
  const auto after = std::lower_bound(times.begin(), times.end(), t - tolerance);
  if (after == times.end()) return std::nullopt;
  const auto k = static_cast<std::size_t>(after - times.begin());
  if (std::abs(times[k] - t) <= tolerance) {
    if (!reference.present(k, partner)) return std::nullopt;
    return Eigen::Vector3d(reference.position(k, partner));
  }
  if (k == 0 || !reference.present(k - 1, partner) || !reference.present(k, partner)) return std::nullopt;
  const double s = (t - times[k - 1]) / (times[k] - times[k - 1]);
  return Eigen::Vector3d((1 - s) * reference.position(k - 1, partner) + s * reference.position(k, partner));
}

}  // namespace

Samples agent_displacement(const CrowdMotion& crowd, std::size_t agent, const CrowdMotion& reference, std::size_t partner,
                           double time_tolerance_s) {
  Samples out;
  for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
    if (!crowd.present(f, agent)) continue;
    const std::optional<Eigen::Vector3d> r = reference_at(reference, partner, crowd.times[f], time_tolerance_s);
    if (r) out.add((Eigen::Vector3d(crowd.position(f, agent)) - *r).norm(), agent, crowd.times[f]);
  }
  return out;
}

}  // namespace throng::check::detail
