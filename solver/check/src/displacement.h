// Private to solver/check: how far each agent is from the same agent of a reference crowd (motion_check.h).
#pragma once

#include "samples.h"

#include <throng/core/crowd_motion.h>

#include <unordered_map>

namespace throng::check::detail {

/// Index of each reference agent by id.
using AgentIndex = std::unordered_map<std::int64_t, std::size_t>;
[[nodiscard]] AgentIndex index_by_id(const CrowdMotion& crowd);

/// The displacement samples of agent `agent` of `crowd` against `reference` (its agent `partner`).
[[nodiscard]] Samples agent_displacement(const CrowdMotion& crowd, std::size_t agent, const CrowdMotion& reference,
                                         std::size_t partner, double time_tolerance_s);

}  // namespace throng::check::detail
