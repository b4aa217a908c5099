// The pose every exporter writes for an agent at a frame: the crowd's own facing and action where it has them,
// else the defaults derived from the path (PathFacing, path_action); and for formats without presence a pose at
// absent frames too: the one at the nearest present frame (the last one, or the first before the agent enters).
#pragma once

#include <throng/core/crowd_motion.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace throng::detail {

/// Streams poses. position() and facing() keep per-agent state: ask each agent's frames in increasing order
/// (an exporter walks frames in order, or one agent through every frame), each accessor on its own; every value
/// is then O(1). Holds a reference to the motion.
class AgentPoses {
 public:
  AgentPoses(const CrowdMotion& motion, const PathPoseRule& rule);

  [[nodiscard]] bool present(std::size_t t, std::size_t n) const noexcept { return motion_.present(t, n); }
  /// Position; where absent the held one.
  [[nodiscard]] Eigen::Vector3d position(std::size_t t, std::size_t n);
  /// Unit quaternion (body frame forward +x, left +y, up +z): stored (held where absent) or derived.
  [[nodiscard]] Eigen::Quaterniond facing(std::size_t t, std::size_t n);
  /// facing(t, n) for every agent n in [first, last), into out[0 .. last − first); derived facings a range at a
  /// time (PathFacing::at_frame: half the time of asking them one by one).
  void facings(std::size_t t, std::size_t first, std::size_t last, Eigen::Quaterniond* out);
  /// Index into action_table(): stored (−1 where absent) or derived from the speed.
  [[nodiscard]] std::int32_t action(std::size_t t, std::size_t n) const;

  /// The crowd's action table, or standard_actions() when its actions are derived.
  [[nodiscard]] const std::vector<ActionKind>& action_table() const;
  [[nodiscard]] bool facing_given() const noexcept { return !motion_.orientations.empty(); }
  [[nodiscard]] bool actions_given() const noexcept { return !motion_.actions.empty(); }

 private:
  const CrowdMotion& motion_;
  PathPoseRule rule_;
  PathFacing derived_;
  /// The first frame agent n is present at (frame_count() if never).
  [[nodiscard]] std::size_t first_present(std::size_t n) const;

  // Per agent, kept by position() and facing() each on its own, set lazily (the first frame asked: a stream that
  // asks present frames only never scans for the first present one).
  std::vector<Eigen::Vector3d> held_position_;   // last present position asked (the first one before entering)
  std::vector<Eigen::Quaterniond> held_facing_;  // the same for stored facings
  std::vector<unsigned char> position_held_, facing_held_;  // 1 once held_position_ / held_facing_ is set
};

/// The heading (radians, CCW from +x) of an orientation: where its forward axis points on the ground plane.
[[nodiscard]] double heading(const Eigen::Quaterniond& q);

}  // namespace throng::detail
