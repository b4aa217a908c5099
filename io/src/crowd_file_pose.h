// The pose elements of a crowd file (facing and action), beside position under /particles/trajectory. Called
// from crowd_file.cpp's writer and reader; the layout is documented in crowd_file.h.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/io/hdf5.h>

#include <cstdint>
#include <functional>
#include <string>

namespace throng::detail {

/// What column `column` of the motion being read holds at `frame`, for messages: "agent 7 (column 2)" in a file
/// with one agent per column; a file with reused slots names the slot and the agent in it at that frame.
using ColumnName = std::function<std::string(std::uint64_t frame, std::uint64_t column)>;

/// Writes `motion`'s orientations and actions, each only when given, as H5MD time-dependent elements sharing
/// position's step and time (hard links), absent agents masked (NaN orientation, action −1), stored as `layout`
/// says. Call after position.
void write_pose_elements(const h5::Group& trajectory, const CrowdMotion& motion, const h5::Layout& layout);

/// Reads the elements back into `motion`, whose positions and ids are read (presence is known): orientations and
/// actions stay empty where the file has none (every file written before them). InputError naming the dataset or
/// attribute for a wrong shape, a present agent's orientation that is not a finite unit quaternion, an action
/// outside the name table, or a table that is missing or malformed. Messages name a present entry with `name`
/// (empty: "agent <motion.ids[column]> (column <column>)").
void read_pose_elements(const h5::Group& trajectory, CrowdMotion& motion, const ColumnName& name = {});

}  // namespace throng::detail
