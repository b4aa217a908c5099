// The stitch job (`throng stitch A.h5 B.h5 [C.h5 ...] -o OUT.h5`, or a `stitch` step of `throng run` with
// `inputs: [a, b, ...]`) and the data it stores under /parameters/throng/stitch. Clips are stitched in order:
// ((A then B) then C) ... (solver/stitch/stitch.h for the method and its decisions).
//
// Job keys (all optional; defaults shown):
//
//   blend_window: 0               # seconds from the joint over which the formations morph (Eq. 11's window), per
//                                 #   side, capped at each clip's duration; 0: automatic — each clip's whole
//                                 #   duration (the paper), shortened only when that exceeds max_blend_vertices
//   max_blend_vertices: 60000     # the automatic window's budget: agents × solved samples (~20 kB each); 0: none
//   matching: world               # world: match agents by distance where they are | centred: after moving both
//                                 #   frames to their centroids
//   alignment: rigid              # rigid (rotation + translation) | translation | none
//   sample_step: 1                # graph samples every so many frames (counted from the joint)
//   formation:
//     max_edge_length: 0          # Ḡ's Delaunay edges longer than this are dropped (0: keep all)
//     edits:                      # as in the edit job, by agent id of the first clip, frames of the stitched
//       - {add: [12, 17], frames: [200, 260]}   #   output (last may be `end`; default all); an edit acts at
//       - {remove: [3, 4]}                      #   the solved samples of each joint's window it overlaps
//   weights: {alpha: 1, beta: 1, alpha_prime: 1, beta_prime: 1}   # Eq. 4 and 9
//   scale_compensation: true
//   features: {min_length: 0.05, degenerate_ratio: 0.001}
//   solver: {backend: eigen, ...}                                 # as in the edit job (throng/io/edit_job.h)
#pragma once

#include <throng/io/config.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>
#include <throng/stitch/stitch.h>

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <vector>

namespace throng {

struct StitchJob {
  stitch::Options options;
};

/// Reads and checks a whole job, then calls job.finish(). ConfigError naming the line.
[[nodiscard]] StitchJob read_stitch_job(const ConfigNode& job);
[[nodiscard]] YAML::Node effective_stitch_job(const StitchJob& job);

/// The stitched crowd and one result per joint (#inputs − 1), each without its crowd (kept in `crowd`).
struct StitchedCrowds {
  CrowdFile crowd;
  std::vector<stitch::Result> joints;
  std::vector<std::size_t> joint_frames;  ///< the output frame of each joint
  /// Per joint, the ids of the clip so far that took part (agents absent somewhere in their clip are left out,
  /// so a later joint may hold fewer agents than an earlier one); row k matches joints[k].second_ids.
  std::vector<std::vector<std::int64_t>> joint_ids;
};

/// Stitches two or more clips in order. The scene is the first input's; provenance credits of every input are
/// kept. Errors from a joint name it ("joint 2 (input 2 then input 3): ..."); fewer than two inputs is a
/// ConfigError. `progress` receives each joint's progress in turn.
[[nodiscard]] StitchedCrowds stitch_crowds(const std::vector<const CrowdFile*>& inputs, const StitchJob& job, Progress& progress);

/// Writes /parameters/throng/stitch/joint_<k> (k from 1) for each joint: first_ids, second_ids int64[N] (the
/// matching: agent of the clip so far, agent of the next clip), attributes frame (output frame of the joint),
/// rotation (radians), translation [2] (metres, applied to the next clip), gap_rms, gap_max (metres), window
/// [2] (frames from the joint to each window edge), window_seconds [2], attribute window_limited (1 when the
/// automatic window was shortened to the budget), matching_distance (metres).
void write_stitch_data(const h5::Group& throng_parameters, const StitchedCrowds& stitched);

}  // namespace throng
