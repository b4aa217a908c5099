#include "agent_poses.h"

#include <cmath>

namespace throng::detail {

AgentPoses::AgentPoses(const CrowdMotion& motion, const PathPoseRule& rule)
    : motion_(motion), rule_(rule), derived_(motion, rule), held_position_(motion.agent_count(), Eigen::Vector3d::Zero()),
      held_facing_(motion.agent_count(), Eigen::Quaterniond::Identity()), position_held_(motion.agent_count(), 0),
      facing_held_(motion.agent_count(), 0) {}

std::size_t AgentPoses::first_present(std::size_t n) const {
  for (std::size_t t = 0; t < motion_.frame_count(); ++t) {
    if (motion_.present(t, n)) return t;
  }
  return motion_.frame_count();
}

Eigen::Vector3d AgentPoses::position(std::size_t t, std::size_t n) {
  if (motion_.present(t, n)) {
    position_held_[n] = 1;
    held_position_[n] = motion_.position(t, n);
  } else if (!position_held_[n]) {
    position_held_[n] = 1;
    if (const std::size_t first = first_present(n); first < motion_.frame_count()) held_position_[n] = motion_.position(first, n);
  }
  return held_position_[n];
}

Eigen::Quaterniond AgentPoses::facing(std::size_t t, std::size_t n) {
  if (!facing_given()) return derived_.at(t, n);
  if (motion_.present(t, n)) {
    facing_held_[n] = 1;
    held_facing_[n] = motion_.orientation(t, n);
  } else if (!facing_held_[n]) {
    facing_held_[n] = 1;
    if (const std::size_t first = first_present(n); first < motion_.frame_count()) held_facing_[n] = motion_.orientation(first, n);
  }
  return held_facing_[n];
}

void AgentPoses::facings(std::size_t t, std::size_t first, std::size_t last, Eigen::Quaterniond* out) {
  if (!facing_given()) return derived_.at_frame(t, first, last, out);
  for (std::size_t n = first; n < last; ++n) out[n - first] = facing(t, n);
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
