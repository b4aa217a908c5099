// Facing and actions through a merge (merge.h): a crowd that carries none gets the documented defaults derived
// from its path (crowd_motion.h: PathFacing, path_action), so the merged crowd carries them for every agent when
// either input does; the two action tables become one.
#pragma once

#include <throng/core/crowd_motion.h>

#include <cstdint>
#include <vector>

namespace throng::stitch::detail {

/// `crowd` with orientations and actions at every present frame: its own where it has them, else the defaults
/// from its path (the standard action table then).
[[nodiscard]] CrowdMotion with_poses(const CrowdMotion& crowd);

/// Appends to `table` the entries of `other` it lacks; returns, for each entry of `other`, its index in `table`.
[[nodiscard]] std::vector<std::int32_t> join_action_tables(std::vector<ActionKind>& table, const std::vector<ActionKind>& other);

}  // namespace throng::stitch::detail
