// Importer for the recorded pedestrian datasets in data/real (ETH/BIWI and UCY "Crowds by Example",
// as collected and converted to metres by the OpenTraj project):
//   obsmat.txt   rows "frame id x z y vx vz vy" (metres, m/s; the z columns are 0: the ground plane is x–y)
//   map.xml      OpenTraj's obstacles: <Line x1 y1 x2 y2> wall segments, <Circle x y radius> pillars (optional)
//   groups.txt   one walking group per line, as agent ids (optional)
//
// Frames: one per annotated video frame, at time = frame / video fps. Annotation runs every 6th video frame (eth)
// or every 10th (the others), i.e. every 0.4 s, but not on one global grid: eth's annotation changes phase across
// stretches where nobody is annotated (frame gaps of 395 and 402). Keeping the annotated frames as they are is
// exact: times are uniform (0.4 s) wherever anybody is present and jump only across those empty stretches.
// Agents are present exactly where annotated. Velocities are the annotators' estimates, kept as the velocity element.
// Species: agents of the k-th walking group get species k (1-based); agents in no group get 0.
// Walls: map.xml's "thickness" attribute is a drawing width in pixels, not metres, so walls get
// `wall_thickness` instead.
// Frame rate and credit come from the content, never from the folder's name: the rows of the recordings throng
// knows (ETH/BIWI eth 15 fps, hotel 25; UCY zara01, zara02, students03 25) are recognised by their row count,
// agent count and first and last frame, whatever the folder is called; otherwise an info.txt beside obsmat.txt
// that states the annotation's time step ("timestep of 0.4 seconds", as ETH ships it) gives the rate with the
// rows' usual frame step; otherwise --fps is needed and no credit is known (give it: import_crowd's credit).
#pragma once

#include <throng/io/crowd_file.h>
#include <throng/io/read_limits.h>

#include <filesystem>
#include <string>

namespace throng {

struct RealDatasetOptions {
  double video_fps = 0.0;        ///< frames per second of the source video; 0: the rate the content states
  double agent_radius = 0.25;    ///< metres, for every agent
  double wall_thickness = 0.1;   ///< metres, total width of map.xml's wall segments
  bool groups = true;            ///< groups.txt beside obsmat.txt becomes species
  bool map = true;               ///< map.xml beside obsmat.txt becomes the scene
};

/// Reads a dataset folder (or its obsmat.txt). Throws IoError (missing files; a folder, device or pipe where a
/// file is expected), InputError naming file and line (malformed rows: every field must be a whole number,
/// "1.5xyz" is refused; frame and id whole numbers from 0 to 2^53; NaN; an id repeated in one frame; a malformed
/// map.xml), InputError with the estimate when the frames × agents arrays exceed `limits` (checked before they
/// are allocated), ConfigError (frame rate neither known from the content nor given, or given and contradicting
/// the known one). Any spelling of the path: "obsmat.txt" from inside the folder, "folder/", ".", "./obsmat.txt".
[[nodiscard]] CrowdFile import_real_dataset(const std::filesystem::path& folder_or_obsmat, const RealDatasetOptions& options,
                                            const ReadLimits& limits = {});

/// map.xml's obstacles (walls `wall_thickness` wide, circles as pillars): for an obstacle map given on its own.
[[nodiscard]] Scene read_obstacle_map(const std::filesystem::path& map_xml, double wall_thickness, const ReadLimits& limits = {});

}  // namespace throng
