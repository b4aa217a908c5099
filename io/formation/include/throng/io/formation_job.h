// The spectral formation control job (`throng formation JOB.yaml -o OUT.h5`, or a `formation` step of
// `throng run`), and the method data it stores in the output under /parameters/throng/formation.
//
// Job file (defaults shown; lengths in metres, times in seconds; individuals are row indices 0..n−1 of the
// keyframes — with from_crowd, the crowd's agent indices):
//
//   keyframes:                        # ≥ 2, times strictly increasing, the same individuals in every one
//     - time: 0
//       positions: [[x, y], ...]      # one row per individual ([x, y, z] for a 3-D formation) ...
//     - time: 10
//       shapes: [{circle: {count: 25, radius: 6}}]   # ... or generated (see throng/io/formation_shapes.h)
//       edits: {...}                  # this keyframe's graph only, after the job-wide edits (same keys as below)
//       sharp: false                  # true: a sharp corner (duplicated in Eq. 5's control points, §4.1)
//   from_crowd:                       # instead of keyframes: the formations of an existing crowd
//     file: crowd.h5                  # in a `throng run` step: leave out to use the step's input crowd
//     frames: [0, 120, 240]           # frame indices (−1 = last)
//     times: [0, 4, 8]                # the keyframes' times (default: the crowd's times at those frames)
//     dimension: 2                    # 2 (x, y) or 3 (x, y, z)
//   ids: [...]                        # the individuals' ids in the output (default 0..n−1; from_crowd: the crowd's)
//   edits:                            # every keyframe's graph (Delaunay, weights 1/distance), in this order:
//     remove: [[3, 4], ...]           # pairs that must be edges
//     add: [[0, 9], ...]              # new edges, weight 1/distance
//     scale:                          # multiply weights (factor > 0) of
//       - {pairs: [[1, 2]], factor: 4}       # these edges,
//       - {members: [0, 1, 2], factor: 4}    # every edge between two of these individuals,
//       - {groups: [brass, drums], factor: 4}  # every edge inside each named hierarchy group (its individuals)
//   hierarchy:                        # none: one flat group up to 2,000 individuals, beyond that built by
//                                     # spectral clustering as {auto: 2000} (§4.4). A tree:
//     name: band                      #   the root; each group has a name, members and/or groups
//     members: [24]                   #   individuals directly in the group
//     groups: [{name: brass, members: [0, 1, 2]}, ...]
//   # or   hierarchy: {sizes: [3, 5, 5, 5, 4, 3]}   one level of groups of consecutive individuals (g0, g1, ...)
//   # or   hierarchy: {nested: [35, 6, 6]}          levels of consecutive individuals: 35 groups of 6 subgroups
//   #                                               of 6 (g0, g0.1, ...), as the `nested` shape orders them
//   # or   hierarchy: {auto: 60}                    spectral clustering, at most 60 items per group (used
//   #                                               only when there are more individuals than that)
//   # or   hierarchy: flat                          one flat group however many individuals
//   frame_rate: 30                    # output frames per second; every keyframe time is a frame
//   tension: 0.5                      # Catmull-Rom τ of Eq. 5, in [0, 1]
//   interpolation: spectral           # spectral | linear | polar (the paper's baselines)
//   keyframe_product: cumulative      # cumulative | paper (Eq. 5 as printed)
//   auto_cluster_size: 250            # the largest group of an automatic hierarchy (≥ 2)
//   reordering: greedy                # none | greedy | max_min (greedy, then the max-min refinement, §4.2)
//   orientation: pca                  # none | pca | procrustes (PCA adjustment, §3.3)
//   isotropy_tolerance: 0.05          # below it (principal variances nearly equal) PCA uses procrustes
//   match_individuals: false          # true: keyframes' rows are not in correspondence; match them
//   radius: 0.25                      # every individual's radius in the output
//   collision:                        # social forces then smoothing (§4.3)
//     enabled: false
//     min_distance: 0.6               # centre to centre, at every frame
//     relaxation_time: 0.3
//     tracking_time: 0.3
//     repulsion_strength: 2.0         # m/s²
//     repulsion_range: 0.2
//     time_step: 0.02
//     smoothing_time: 0.25
//     smoothing_passes: 2
//     projection_sweeps: 200
//
// Exit codes: job syntax, unknown keys, options out of range, edits naming non-edges, a malformed hierarchy
// are ConfigErrors (2). The formations themselves are data: a keyframe with a different number of individuals
// or a different dimension, a position or time that is not a finite number (.nan, .inf), times not
// increasing, two individuals at the same position, a disconnected graph, keyframes closer than
// collision.min_distance are InputErrors (3), naming the keyframe. Every message about something written in
// the job starts with its file:line:column — the keyframe, the edits list, the hierarchy — also when the solver
// finds the problem (the places travel in Keyframe::where, AdjacencyEdits::where, Group::where); keyframes from
// a crowd are named by the crowd file and frame. See throng/formation/formation.h for the method.
#pragma once

#include <throng/formation/runner.h>
#include <throng/io/job_file.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>
#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <vector>

namespace throng {

/// Keyframes taken from a crowd: which file (empty: the step's input crowd) and frames.
struct FormationCrowdSource {
  std::string file;          ///< resolved against the job file's folder (ConfigNode::as_path)
  std::vector<long> frames;  ///< negative counts from the end (−1 = last)
  std::vector<double> times; ///< empty: the crowd's times at those frames
  int dimension = 2;
};

/// A parsed formation job (read_job): the method's job (problem, options: formation/runner.h) and how it was
/// written. With `from_crowd`, problem.keyframes is empty until resolve_formation_keyframes.
struct FormationJob : formation::Job {
  std::optional<FormationCrowdSource> from_crowd;
  YAML::Node keyframes_yaml;   ///< the keyframes as written (positions or shapes), for the effective job
  YAML::Node hierarchy_yaml;   ///< the hierarchy as written
  YAML::Node edits_yaml;       ///< the job-wide edits as written
};

/// Reads and checks a whole job, then calls job.finish() (unknown keys are errors). Generated shapes are
/// expanded. ConfigError / InputError as the header comment says.
void read_job(const ConfigNode& node, FormationJob& job);

/// With from_crowd: fills problem.keyframes (and ids, unless given) from `crowd` at the job's frames (nothing
/// to do without). InputError for a frame out of range or an agent absent at a keyframe frame.
void resolve_formation_keyframes(FormationJob& job, const Crowd* crowd);

/// The job with every option at its effective value (for --print-config and the output's provenance).
[[nodiscard]] YAML::Node effective_job(const FormationJob& job);

}  // namespace throng

namespace throng::formation {

/// Writes the method data into /parameters/throng/formation (the report's fields join them, formation/runner.h):
///   keyframes/time            float64[K]        seconds
///   keyframes/frame           int64[K]          the keyframe's frame in the output
///   keyframes/position        float64[K][N][d]  each individual's keyframe position (after matching)
///   keyframes/correspondence  int64[K][N]       the keyframe row (as given) taken by each individual
///   keyframes/edges_<k>       int32[E][2]       keyframe k's graph edges between individuals (after edits)
///   groups/name               string[G]         the hierarchy's groups (species = group index)
///   groups/parent             int64[G]          −1 for the root
void write_data(const h5::Group& record, const Run& run);

}  // namespace throng::formation
