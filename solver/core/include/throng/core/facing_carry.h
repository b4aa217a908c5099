// Carrying an input's facing and actions through a deformation of its paths (edit, collide, stitch).
//
// Rule (issue 13): an agent keeps its facing at the same angle to its path as in the input. At a frame where the
// agent moves (path speed ≥ PathPoseRule::standing_speed) both before and after the deformation, the facing is
// turned about +z by the change of its path tangent's yaw there (after − before, wrapped to (−π, π]). Where it
// stands in either (the tangent means nothing there), the change of the nearest frame of the same range where it
// moves in both is used (the earlier one on a tie); with no such frame the facing is kept. A standing turn in the
// input is thus kept as a standing turn, and an agent walking sideways keeps walking sideways.
//
// Actions: an action whose table entry is one of the standard speed classes (walk, stand, run, no prop) is
// re-derived where the deformation moved the agent's path speed into another class (PathPoseRule thresholds):
// a drag that doubles a walker's speed makes it run. Where the class did not change the input's action is kept
// (an agent the input marked standing while it drifted keeps standing), and any other entry (a tiled patch's
// label, an action with a prop) passes through unchanged. A class the table lacks is appended to the table.
#pragma once

#include <throng/core/crowd_motion.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace throng {

/// How fast a carried facing may turn (rad/s): 270°/s, a brisk turn on the spot (sketch's own limit, below the
/// checker's default of 360°/s). A deformation that bends a path sharply, or a stitch that hands an agent from one
/// clip's facing to another's at the seam, turns the facing at most this fast (limit_facing_rate).
inline constexpr double carried_max_turn_rate = 1.5 * 3.14159265358979323846;

/// Turns agent `agent`'s facing at frames first+1..last (where it and the frame before are present) toward its
/// current value by at most max_rate × the frame interval from the frame before (slerp along the shorter arc),
/// in order, so the facing never turns faster than max_rate (rad/s > 0). Nothing without orientations.
void limit_facing_rate(CrowdMotion& motion, std::size_t agent, std::size_t first, std::size_t last, double max_rate);
/// The same for every agent over every frame.
void limit_facing_rate(CrowdMotion& motion, double max_rate);

/// The quaternion of a turn by `yaw` radians about +z applied to `q` (world frame): R_z(yaw) q, normalised.
[[nodiscard]] Eigen::Quaterniond turned_by_yaw(const Eigen::Quaterniond& q, double yaw);

/// The yaw (radians, (−π, π]) that takes direction `from` to direction `to` in the ground plane.
[[nodiscard]] double yaw_change(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

/// The frames of one agent carried: frames first..last of agent `after_agent` in `after` came from frames
/// first + frame_offset.. of agent `before_agent` in `before` (frame_offset may be negative: a stitched clip's
/// second part). `rotation` is a rigid turn (radians about +z) applied to `before` besides the deformation (the
/// stitch's alignment of G′; 0 otherwise): the tangent change is measured against the turned input.
struct CarriedSpan {
  std::size_t before_agent = 0;
  std::size_t after_agent = 0;
  std::size_t first = 0, last = 0;  ///< frames of `after`, inclusive
  std::ptrdiff_t frame_offset = 0;  ///< frame of `before` = frame of `after` + frame_offset
  double rotation = 0.0;
  /// `before`'s action index → `after`'s table (a second clip whose table differs); nullptr: the same indices.
  const std::vector<std::int32_t>* action_map = nullptr;
  /// rad/s: the carried facing turns no faster (limit_facing_rate); infinity: the rule above exactly.
  double max_turn_rate = carried_max_turn_rate;
};

/// Writes `after`'s orientations and actions over the span from `before`'s by the rule above, then limits the
/// facing's turn rate to carried_max_turn_rate from the frame before the span to its end. `before` must have
/// orientations (else nothing is written); `after` must already hold orientations and actions of its size (and,
/// for actions, `before`'s action table: entries may be appended). Frames where the agent is absent in `after`
/// are left as they are.
void carry_facing(const CrowdMotion& before, CrowdMotion& after, const CarriedSpan& span, const PathPoseRule& rule = {});

/// The common case: `after` has `before`'s agents and frames (same order), only positions moved. Gives `after`
/// `before`'s orientations, actions and action table: carried by the rule above for every agent in
/// `changed_agents` (indices), copied for the rest. None when `before` has none.
void carry_facing_same_frames(const CrowdMotion& before, CrowdMotion& after, const std::vector<std::size_t>& changed_agents,
                              const PathPoseRule& rule = {}, double max_turn_rate = carried_max_turn_rate);

/// Fills what `motion` lacks of orientations and actions with the path's default (PathFacing, path_action; the
/// table becomes standard_actions() when actions are filled): for a part that has none joined to one that has.
void derive_path_pose(CrowdMotion& motion, const PathPoseRule& rule = {});

/// The index of every entry of `from` in `into`, appending the entries `into` lacks.
[[nodiscard]] std::vector<std::int32_t> merge_action_tables(const std::vector<ActionKind>& from, std::vector<ActionKind>& into);

}  // namespace throng
