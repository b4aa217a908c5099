// Merging two groups into one (paper §3: "multiple groups can be merged together to form a larger group";
// METHODS.md §1.1: two groups in the same time span become one graph). The merged crowd holds both groups'
// agents over a shared timeline; any graph built on it (editing, stitching) triangulates the union, so formation
// edges join the two groups where they are neighbours.
//
// Decisions:
//  * Timeline. span = overlap (default, the paper's case): the frames where both crowds exist; crowds whose times
//    do not overlap are an InputError. span = union: from the earlier start to the later end, each agent present
//    where its own crowd is (building a longer scene out of clips placed in time).
//  * Frame times. The merged frames are every frame time of either crowd within the span, times closer than
//    time_tolerance counted as one (the first crowd's). Crowds cut from the same scene, or retimed by whole frames,
//    share their frame times and nothing is interpolated. Otherwise each crowd is evaluated at the other's frame
//    times through not-a-knot cubic splines over each agent's run of present frames (throng/timewarp), and the
//    report counts those frames. Velocities are kept only when both crowds have them and nothing was interpolated.
//  * Ids. The first crowd's agents come first and keep their ids. If any id of the second crowd clashes with one
//    of the first, on_id_clash = shift (default) adds the same offset to every id of the second crowd, the least
//    that puts them all above the first crowd's largest id (so its agents stay distinct and in order, and the
//    offset is reported); on_id_clash = error makes a clash an InputError naming the ids.
//  * Agents present at no merged frame (outside the overlap) are left out and counted.
//  * Scene: the union — both crowds' obstacles; the region, if only one has one, is kept; if both have one, the
//    box covering both, periodic only on axes where both are periodic and their extents agree.
//  * Formation edges for the file: the Delaunay triangulation of the union at the first merged frame where both
//    groups have agents (throng/graph/delaunay.h), minus edges longer than max_edge_length when it is set; the
//    report counts the edges joining the two groups.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/scene.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace throng::stitch {

enum class MergeSpan { overlap, union_of_spans };
enum class IdClash { shift, error };

struct MergeOptions {
  MergeSpan span = MergeSpan::overlap;
  IdClash on_id_clash = IdClash::shift;
  /// Seconds: frame times of the two crowds closer than this are one frame.
  double time_tolerance_s = 1e-6;
  /// Metres: the stored formation edges longer than this are dropped (0 keeps them all), as the edit job's
  /// formation.max_edge_length does for its graph. Groups placed far apart in one scene (a town) are then not
  /// joined by long edges; groups side by side still are.
  double max_edge_length = 0.0;
};

struct MergeReport {
  std::size_t frames = 0;
  double first_time = 0, last_time = 0;       ///< seconds
  std::int64_t id_shift = 0;                  ///< added to the second crowd's ids (0: no clash)
  std::size_t interpolated_frames_first = 0;  ///< merged frames where the first crowd was interpolated
  std::size_t interpolated_frames_second = 0;
  std::size_t left_out_first = 0, left_out_second = 0;  ///< agents present at no merged frame
  std::size_t formation_frame = 0;            ///< the frame the formation edges were taken at
  std::size_t cross_edges = 0;                ///< formation edges joining an agent of each group there
  bool velocities_dropped = false;
};

/// The merged crowd: agent j < first_agents.size() is the first crowd's agent first_agents[j], the others are the
/// second crowd's second_agents[j − first_agents.size()] (indices into the inputs).
struct Merged {
  CrowdMotion crowd;
  std::vector<std::size_t> first_agents, second_agents;
  Scene scene;
  std::vector<std::array<std::int32_t, 2>> formation_edges;  ///< agent index pairs (i < j), sorted
  MergeReport report;
};

/// Merges `second` into `first` (see above). Throws ConfigError for a bad tolerance, InputError for spans that do
/// not overlap (span = overlap), an overlap holding fewer than 2 frames, or an id clash with on_id_clash = error.
[[nodiscard]] Merged merge(const CrowdMotion& first, const Scene& first_scene, const CrowdMotion& second,
                           const Scene& second_scene, const MergeOptions& options = {});

/// The union of two scenes, as merge() makes it.
[[nodiscard]] Scene merge_scenes(const Scene& first, const Scene& second);

}  // namespace throng::stitch
