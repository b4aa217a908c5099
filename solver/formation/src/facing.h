// The facing and action of every individual of a formation (CrowdMotion::orientations, actions, action_table),
// from its own model: the direction of travel, and the facings keyframes give.
//
//   travel facing  along the chord of the individual's path over FacingOptions::smoothing_s centred on the frame
//                  (shifted inside the frames at the ends): the direction of travel without the frame-to-frame
//                  jitter that collision avoidance adds. Where that chord's speed is below rule.standing_speed
//                  the individual keeps its last facing (before it first moves: where it first moves; never: +x),
//                  core's standing rule. 2-D formations: a yaw about +z. 3-D formations: yaw and pitch along the
//                  chord (core's facing_along), and with FacingOptions::bank a roll into turns as a coordinated
//                  turn flies it: tan(bank) = lateral acceleration / g, the acceleration from the same window.
//                  It turns toward that orientation at most FacingOptions::max_turn_rate_rad_s (along the shorter
//                  arc): an individual whose path reverses turns about over a second instead of in one frame.
//   given facings  a keyframe's facings (Keyframe::facings) hold exactly at its frame. Between two keyframes that
//                  both give them the facing turns along the shorter arc (slerp; in 2-D the shorter yaw) linearly in
//                  time; between one that gives them and one that does not it turns from the given facing to the
//                  travel facing (or back) the same way; between two that do not it is the travel facing.
//   action         by the chord's speed: stand below rule.standing_speed, run from rule.running_speed, walk
//                  between (standard_actions()).
// Per individual independent: the same bits for any thread count.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/formation/formation.h>

#include "spline.h"

#include <Eigen/Geometry>

#include <vector>

namespace throng::formation {

/// Fills motion.orientations, actions and action_table from motion.positions (present everywhere).
/// `given[k]`: keyframe k's facings, empty or one unit quaternion per individual (in motion's agent order).
void fill_facings(CrowdMotion& motion, const Timeline& timeline, const std::vector<std::vector<Eigen::Quaterniond>>& given,
                  int dimension, const FacingOptions& options);

}  // namespace throng::formation
