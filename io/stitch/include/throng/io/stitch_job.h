// The stitch job (`throng stitch A.h5 B.h5 [C.h5 ...] -o OUT.h5`, or a `stitch` step of `throng run` with
// `inputs: [a, b, ...]`) and the data it stores under /parameters/throng/stitch. Clips are stitched in order:
// ((A then B) then C) ... (solver/stitch/stitch.h for the method and its decisions; the options' schema in
// solver/stitch/schema.h, the runner in jobs.h).
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

#include <throng/io/job_file.h>
#include <throng/stitch/jobs.h>

namespace throng::stitch {

/// Reads and checks a whole job (the options, the formation edits), then calls node.finish(). ConfigError naming
/// the line. The effective job is job_file.h's.
void read_job(const ConfigNode& node, StitchJob& job);
/// Writes beside the report's joints (stitch/jobs.h) in /parameters/throng/stitch/joint_<k> (k from 1):
/// first_ids, second_ids int64[N], the matching (agent of the clip so far, agent of the next clip).
void write_data(const h5::Group& record, const StitchRun& run);

}  // namespace throng::stitch
