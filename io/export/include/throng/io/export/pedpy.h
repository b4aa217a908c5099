// Export to the HDF5 layout of the Pedestrian Dynamics Data Archive, which JuPedSim writes and PedPy loads
// (pedpy.load_trajectory_from_ped_data_archive_hdf5, load_walkable_area_from_ped_data_archive_hdf5), so density,
// speed and flow can be computed on throng's crowds:
//
//   /trajectory     compound rows {frame int64, id int64, x, y, z, ox, oy float64}, one per present agent and
//                   frame, frame-major: the frame number from 0, the agent's id, its position (metres, x/y the
//                   ground plane, z up) and the unit vector of its facing on the ground (ox, oy). Attribute fps
//                   (float64, frames per second) and a description attribute per column, as JuPedSim writes.
//   wkt_geometry    root attribute (string): the walkable area, one WKT POLYGON with holes (see walkable_area)
//
// PedPy counts frames at a constant rate, so the crowd's frames must be evenly spaced (InputError otherwise:
// a time-warped crowd is resampled first). The data is not compressed (h5repack compresses it if wanted).
#pragma once

#include <throng/io/crowd_file.h>
#include <throng/io/export/pose_rule.h>

#include <filesystem>

namespace throng {

struct PedpyOptions {
  enum class WalkableArea {
    if_obstacles,  ///< write wkt_geometry when the crowd has static obstacles (the default)
    required,      ///< write it; ConfigError (exit 2) when the crowd has no static obstacles to build it from
    none,          ///< never
  };
  WalkableArea walkable_area = WalkableArea::if_obstacles;
};

/// Writes `crowd` to `output` atomically, frame by frame. IoError when the folder does not exist or a write
/// fails; InputError for uneven frame times or fewer than two frames; ConfigError as WalkableArea says.
void export_pedpy(const CrowdFile& crowd, const std::filesystem::path& output, const PedpyOptions& pedpy = {},
                  const ExportOptions& options = {});
/// The same for a crowd file on disk (read once).
void export_pedpy(const std::filesystem::path& crowd, const std::filesystem::path& output, const PedpyOptions& pedpy = {},
                  const ExportOptions& options = {});

}  // namespace throng
