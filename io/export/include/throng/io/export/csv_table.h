// Export to CSV tables for tools that take tables (Houdini's Table Import, Blender through a short script,
// spreadsheets, pandas). Two files:
//
//   OUT.csv            one row per present agent and frame, frame-major, agents in file order:
//                      frame,time,id,x,y,z,qx,qy,qz,qw,heading_deg,action,prop,radius,species
//                      frame is the 0-based frame number, time in seconds, x y z in metres (z up), qx..qw the
//                      facing as a unit quaternion (scalar last, as Houdini's orient), heading_deg where the
//                      forward axis points on the ground (degrees CCW from +x), action and prop the names from
//                      the action table (prop empty for none)
//   OUT_obstacles.csv  one row per obstacle point: obstacle,name,kind,size,point,x,y,moving — a circle's centre
//                      (size = radius), a convex polygon's vertices counter-clockwise, a wall's two end points
//                      (size = thickness); a moving obstacle where it stands at the crowd's first frame (moving = 1).
//                      Written with its header alone for a crowd without obstacles.
//
// Numbers are in the shortest form that reads back to the same double; text fields are quoted when they hold a
// comma, a quote or a line break (RFC 4180). Both files are written atomically.
#pragma once

#include <throng/io/crowd_file.h>
#include <throng/io/export/pose_rule.h>

#include <filesystem>

namespace throng {

/// Writes `crowd` to `output` and its obstacles to csv_obstacles_path(output). IoError when the folder does not
/// exist or a write fails (neither file is left behind).
void export_csv(const CrowdFile& crowd, const std::filesystem::path& output, const ExportOptions& options = {});
/// The same for a crowd file on disk (read once).
void export_csv(const std::filesystem::path& crowd, const std::filesystem::path& output, const ExportOptions& options = {});

/// OUT_obstacles.csv beside OUT.csv.
[[nodiscard]] std::filesystem::path csv_obstacles_path(const std::filesystem::path& output);

}  // namespace throng
