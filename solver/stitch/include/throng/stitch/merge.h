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
//  * Joining by identity (join_by = id; default none): an agent of the second crowd whose id is that of a kept
//    agent of the first is the same agent, not a clash — one agent, the first crowd's radius and species, its
//    samples from both crowds. Where only one crowd has a sample of its own at a merged frame (the other none or an
//    interpolated one) that sample is taken; where both have one (frames both share, such as the frame where
//    `split` cut a recording) they must lie within join_tolerance (default 1 µm), and are then one sample (the
//    first's); farther apart is an InputError (exit 3) naming the id, the time and both frames: two different
//    agents share that id. Ids are never shifted when joining. So the two halves of a recording cut by
//    split_at_frame, merged with join_by id and span union, are the recording again: the same agents with the same
//    ids, positions at every frame and obstacles. Without join_by (the default) a shared id is a clash as above:
//    the second crowd's agents are renumbered (on_id_clash = shift), and a person seen in both clips becomes two.
//  * Agents present at no merged frame (outside the overlap) are left out and counted.
//  * Facing and actions: when either crowd carries orientations or actions the merged crowd carries both for
//    every agent — copied at a crowd's own frames, at interpolated ones slerped and the earlier sample's action
//    (timewarp::resample_crowd), and for a crowd that carries none the defaults from its path (PathFacing,
//    path_action). The action tables become one: the first crowd's entries, then the second's that are new.
//  * Scene: the union — both crowds' obstacles, an obstacle of the second identical to one already there (same
//    shape, motion and name, exactly) kept once (the clips of one scene share its walls); the region, if only one has one, is kept; if both have one, the
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
enum class JoinBy { none, id };

struct MergeOptions {
  MergeSpan span = MergeSpan::overlap;
  IdClash on_id_clash = IdClash::shift;
  /// Seconds: frame times of the two crowds closer than this are one frame.
  double time_tolerance_s = 1e-6;
  /// Metres: the stored formation edges longer than this are dropped (0 keeps them all), as the edit job's
  /// formation.max_edge_length does for its graph. Groups placed far apart in one scene (a town) are then not
  /// joined by long edges; groups side by side still are.
  double max_edge_length = 0.0;
  /// none: every agent of the second crowd is another agent; id: agents with the same id are one (see above).
  JoinBy join_by = JoinBy::none;
  /// Metres: joined by id, two samples of one agent at one frame farther apart than this are an error.
  double join_tolerance_m = 1e-6;
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
  std::size_t joined = 0;                     ///< agents of the second crowd joined to the first's by id
  std::size_t shared_obstacles = 0;           ///< obstacles of the second crowd identical to one of the first: kept once
};

/// The merged crowd: agent j < first_agents.size() is the first crowd's agent first_agents[j] (joined by id, with
/// the samples of the second crowd's agent of that id), the others are the second crowd's
/// second_agents[j − first_agents.size()] (indices into the inputs).
struct Merged {
  CrowdMotion crowd;
  std::vector<std::size_t> first_agents, second_agents;
  Scene scene;
  std::vector<std::array<std::int32_t, 2>> formation_edges;  ///< agent index pairs (i < j), sorted
  MergeReport report;
};

/// Merges `second` into `first` (see above). Throws ConfigError for a bad tolerance, InputError for spans that do
/// not overlap (span = overlap), an overlap holding fewer than 2 frames, an id clash with on_id_clash = error, or
/// (join_by = id) one id at two places at one frame.
[[nodiscard]] Merged merge(const CrowdMotion& first, const Scene& first_scene, const CrowdMotion& second,
                           const Scene& second_scene, const MergeOptions& options = {});

/// The union of two scenes, as merge() makes it: identical obstacles once. `shared`: set to how many of the
/// second scene's obstacles were already in the first.
[[nodiscard]] Scene merge_scenes(const Scene& first, const Scene& second, std::size_t* shared = nullptr);

}  // namespace throng::stitch
