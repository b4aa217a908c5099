// Private to solver/check: the kinematic measures of one agent (speed, accelerations, turning and facing
// rates; motion_check.h gives the definitions).
#pragma once

#include "samples.h"

#include <throng/core/crowd_motion.h>

namespace throng::check::detail {

struct AgentKinematics {
  Samples speed, acceleration, tangential, normal, turning, facing;
};

/// The measures of agent `agent` of `crowd`; `facing` is #frames × #agents yaw or null.
[[nodiscard]] AgentKinematics agent_kinematics(const CrowdMotion& crowd, std::size_t agent, const Settings& settings,
                                               const FacingSeries* facing);

}  // namespace throng::check::detail
