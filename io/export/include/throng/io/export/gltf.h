// Export to binary glTF 2.0 (.glb) for Blender, Houdini, Maya, Unreal, three.js and every glTF viewer.
//
//   nodes       one per agent, named "agent_<id>", instancing one proxy mesh (an arrowhead prism whose tip shows
//               the facing, 4 radii tall), scale = the agent's radius; extras {"id", "species", "radius"}
//   animation   one, "crowd": per agent a translation and a rotation channel sampled at every frame (LINEAR,
//               times in seconds from the crowd's first frame), and for an agent absent at some frames a scale
//               channel (STEP) that is 0 while it is absent (its position and facing are held there)
//   asset       extras {"throng": {"start_time_s", "credits", "action_names", "action_props"}}
//
// Axes: glTF is +Y up with a character's front along +Z. The crowd's (x, y, z) (z up) is written as
// (x, z, −y), which every importer that converts to Z-up (Blender) turns back into (x, y, z); the proxy's
// forward is its local +Z, so a character model put in its place faces the right way. Values are float, as
// glTF stores them: times, positions and quaternion components to single precision.
#pragma once

#include <throng/io/crowd_file.h>
#include <throng/io/export/pose_rule.h>

#include <filesystem>

namespace throng {

/// Writes `crowd` to `output` atomically, agent by agent (a few MB of buffer beside the crowd); IoError when the
/// folder does not exist or a write fails.
void export_gltf(const CrowdFile& crowd, const std::filesystem::path& output, const ExportOptions& options = {});
/// The same for a crowd file on disk (read once).
void export_gltf(const std::filesystem::path& crowd, const std::filesystem::path& output, const ExportOptions& options = {});

}  // namespace throng
