// Export to USD ASCII (.usda) for Houdini Solaris, Golaem, Omniverse and every USD pipeline: one
// UsdGeomPointInstancer whose instances are the agents.
//
//   layer metadata   upAxis "Z", metersPerUnit 1 (the crowd's own axes and units), timeCodesPerSecond and
//                    framesPerSecond the crowd's frame rate, startTimeCode 0, endTimeCode the last frame;
//                    customLayerData "throng:startTime" (seconds of time code 0) and "throng:credits"
//   /Crowd           Xform, the default prim
//   /Crowd/Agents    PointInstancer:
//     ids            int64[N], the agents' ids (constant)
//     protoIndices   int[N], the agent's species' prototype (constant)
//     prototypes     one proxy Mesh per species under Prototypes (an arrowhead pointing along +x, coloured by
//                    species), drawn at scales = (radius, radius, radius)
//     positions      point3f[N] per frame (time samples); an absent agent at its nearest present position
//     orientations   quath[N] per frame, (w, x, y, z) as USD writes quaternions: the facing
//     invisibleIds   int64[] per frame: the ids of the agents absent at that frame
//     primvars:throng:action  int[N] per frame (interpolation "vertex": one per instance), an index into
//                    throng:actionNames / throng:actionProps (string[], the action table stored once)
//     primvars:throng:species int[N] (constant)
//
// Time code k is frame k when the frames are evenly spaced; otherwise time codes are (t − t0) × rate with the
// mean frame rate, so every frame keeps its exact time. Positions are float (USD's point3f: a 1 km crowd is
// placed to 0.1 mm), orientations half precision (USD's quath, read by every USD version: ±0.06° of heading).
#pragma once

#include <throng/io/crowd_file.h>
#include <throng/io/export/pose_rule.h>

#include <filesystem>

namespace throng {

/// Writes `crowd` to `output` atomically; IoError when the folder does not exist or a write fails.
void export_usd(const CrowdFile& crowd, const std::filesystem::path& output, const ExportOptions& options = {});
/// The same for a crowd file on disk (read once).
void export_usd(const std::filesystem::path& crowd, const std::filesystem::path& output, const ExportOptions& options = {});

}  // namespace throng
