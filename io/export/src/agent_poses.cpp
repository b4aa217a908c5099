#include "agent_poses.h"

#include <cmath>

namespace throng::detail {

AgentPoses::AgentPoses(const CrowdMotion& motion, const PathPoseRule& rule)
    : motion_(motion), rule_(rule), derived_(motion, rule), held_position_(motion.agent_count(), Eigen::Vector3d::Zero()),
      held_facing_(motion.agent_count(), Eigen::Quaterniond::Identity()) {
  for (std::size_t n = 0; n < motion.agent_count(); ++n) {
    const auto [first, last] = motion.presence_span(n);
    if (last <= first) continue;
    held_position_[n] = motion.position(first, n);
    if (facing_given()) held_facing_[n] = motion.orientation(first, n);
  }
}

Eigen::Vector3d AgentPoses::position(std::size_t t, std::size_t n) {
  if (motion_.present(t, n)) held_position_[n] = motion_.position(t, n);
  return held_position_[n];
}

Eigen::Quaterniond AgentPoses::facing(std::size_t t, std::size_t n) {
  if (!facing_given()) return derived_.at(t, n);
  if (motion_.present(t, n)) held_facing_[n] = motion_.orientation(t, n);
  return held_facing_[n];
}

std::int32_t AgentPoses::action(std::size_t t, std::size_t n) const {
  if (!actions_given()) return path_action(motion_, t, n, rule_);
  return motion_.present(t, n) ? motion_.action(t, n) : -1;
}

const std::vector<ActionKind>& AgentPoses::action_table() const {
  return actions_given() ? motion_.action_table : standard_actions();
}

double heading(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d f = q * Eigen::Vector3d::UnitX();
  return std::atan2(f.y(), f.x());
}

}  // namespace throng::detail
