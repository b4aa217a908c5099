// CSV tables `time,id,x,y,z` for tools that take tables (Blender's CSV import, Houdini's Table Import,
// spreadsheets): one row per present agent per frame, frame-major, agents in file order; numbers in the shortest
// form that reads back to the same double.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/io/read_limits.h>

#include <filesystem>

namespace throng {

/// Writes `motion` atomically to `path`.
void write_csv(const std::filesystem::path& path, const CrowdMotion& motion);

/// Reads a `time,id,x,y,z` table (header required; rows in any order). Frames are the distinct times, agents
/// the distinct ids (sorted); an agent is absent where it has no row. Every cell must be a whole number (spaces
/// around it allowed): "1.5xyz" is an error. InputError naming the line for a malformed row, a non-finite value
/// or an id repeated at one time; IoError for a missing file, a folder or a device; InputError with the estimate
/// when the frames × agents array the table becomes exceeds `limits` (checked before it is allocated).
[[nodiscard]] CrowdMotion read_csv(const std::filesystem::path& path, double agent_radius = 0.25, const ReadLimits& limits = {});

}  // namespace throng
