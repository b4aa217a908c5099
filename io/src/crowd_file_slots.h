// Crowd files whose columns are reused slots (H5MD's variable particle set): id/value[T][S] names the agent in
// each slot at each frame, and a slot holds several agents one after another. read_crowd_file (crowd_file.cpp)
// reads the per-frame arrays as they are stored, [T][S], and hands them here to become one column per agent. The
// rules are documented in crowd_file.h.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/io/hdf5.h>

#include <cstdint>
#include <vector>

namespace throng::detail {

/// True when some column of `per_frame_id` ([frames][slots], row-major; empty when the file has no id/value)
/// holds two different ids ≥ 0: the file is slotted. Otherwise every column is one agent (the classic layout).
[[nodiscard]] bool has_reused_slots(const std::vector<std::int64_t>& per_frame_id, std::uint64_t slots);

/// The agents of a slotted file, one column each, from `slots` (times and positions [T][S][3] as read from the
/// file) and `per_frame_id` (id/value [T][S]): lists the agents (/parameters/throng/agents under `root`, else
/// the ids in order of first appearance), charges their columns to the file's budget before building them, reads
/// velocity, orientation and action as slots and moves every present entry to its agent's column (NaN, −1 where
/// absent). InputError for an id not listed, an id listed twice, one agent in two slots at one frame, a present
/// slot's non-finite position, the pose elements' defects, or columns beyond the memory limit.
[[nodiscard]] CrowdMotion read_slotted_motion(const h5::Group& root, const h5::Group& trajectory, CrowdMotion slots,
                                              std::vector<std::int64_t> per_frame_id, std::uint64_t slot_count);

}  // namespace throng::detail
