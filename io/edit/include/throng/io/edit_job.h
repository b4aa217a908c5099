// The group motion editing job (`throng edit CROWD.h5 --job EDIT.yaml -o OUT.h5`, or an `edit` step of
// `throng run`), and the method data it stores in the output under /parameters/throng/edit.
//
// Job file (every key optional; defaults shown; agents by id, frames are indices into the input's frames — in
// pins, drags and constraints a negative frame counts back from the clip's last frame, −1 being the last —
// lengths in metres, angles in radians, velocities in m/s):
//
//   clip_only: false                  # false: the whole input crowd with the clip edited (other agents and frames
//                                     # as they are); true: only the clip (its frames, the agents it edited)
//   clip:
//     first_frame: 0
//     last_frame: end                 # a frame index, or end (the input's last frame)
//     agents: [3, 5, 8]               # default: every agent present over the whole clip (others are left out)
//     sample_step: 1                  # sample every so many frames; the clip's last frame is always a sample
//   formation:
//     max_edge_length: 0              # Delaunay edges longer than this are dropped (0: keep all)
//     edits:                          # applied in order, at the samples in their frame range
//       - {add: [12, 17], frames: [0, 200]}   # add the edge between agents 12 and 17 (frames: default whole clip)
//       - {remove: [3, 4]}                    # remove the edge between agents 3 and 4
//     splits:                         # branch splits, after the edits: every formation edge between these agents
//                                     # and the rest of the clip is cut at the samples of the range (the paper's
//                                     # battlefield branches); each agent keeps its own trajectory's features
//       - {agents: [1, 3, 5], frames: [600, end]}  # frames: default the whole clip (indices, last may be end)
//   weights: {alpha: 1, beta: 1, alpha_prime: 1, beta_prime: 1}   # α, β of Eq. 4 and α′, β′ of Eq. 9
//   scale_compensation: true          # step 2 (Eq. 8–10); false keeps step 1's result
//   features: {min_length: 0.05, degenerate_ratio: 0.001}        # see throng/graph/features.h
//   solver:
//     backend: eigen                  # eigen | petsc (the --backend flag overrides)
//     blas_threads: 1
//     relative_tolerance: 1e-12       # petsc: ‖Qx − b‖ ≤ tol·‖b‖
//     max_iterations: 2000            # petsc, per solve
//     petsc_prefix: throng_           # PETSc options prefix (PETSC_OPTIONS="-throng_ksp_type gmres" ...)
//     petsc_options: ""               # e.g. "-pc_type hypre", written without the prefix
//     constraint_tolerance: 1e-8      # a constraint is met when |c·x − d| ≤ tol·(1 + ‖x‖∞)
//     schur_cache_megabytes: 512
//   local:                            # local edits (throng/edit/local_edit.h, docs/commands/scale.md)
//     parts: 0                        # 0 = global solve; auto = parts of about vertices_per_part vertices; or a
//                                     # METIS part count (the --local-parts flag overrides: N or auto)
//     vertices_per_part: 500          # part size for parts: auto (vertices = agents × samples of the clip)
//     halo: 1                         # parts within this many hops of the reached ones are solved too; -1 = all connected (--halo)
//     seed: 1                         # METIS seed: same seed, same parts
//     max_cached_regions: 8           # factorised regions kept for later drags (matters to interactive use)
//   guard:                            # plausibility after the edit (timewarp/guard.h; docs/commands/edit.md)
//     enabled: true                   # false: the paper's edit exactly (and before a timewarp step, which
//                                     # needs the edit's own frames)
//     max_speed_ratio: 1.25           # speed ≤ this × the input's fastest (a slow-down where it is not)
//     max_acceleration: 3             # m/s²: frames beyond this and the input's own are smoothed, the
//                                     # request's frames held
//     ramp_time: 1                    # s; smoothing_time 0.5 s, max_window_time 2 s as in stitch
//   pins:                             # an agent at a frame stays (or is put) somewhere
//     - {agent: 12, frame: 40}                    # where it is
//     - {agent: 12, frame: 80, position: [3, 4]}
//   drags:                            # selected vertices move rigidly: p ↦ pivot + R(rotation)(p − pivot) + offset
//     - agents: [1, 2, 3]             # default: every agent of the clip
//       frames: [0, 10]               # default: the whole clip; [-25, end] = the last 25 frames
//       offset: [5, 0]
//       rotation: 0.5
//       pivot: [0, 0]                 # default: the centroid of the selected vertices
//   constraints:                      # general linear constraints (at the samples in their frame range)
//     - {type: relative_position, agent: 12, other: 17, frames: [100, 120], offset: [1, 0]}  # default offset: original
//     - {type: velocity, agent: 12, frame: 50, velocity: [1.2, 0]}    # (p(f+1) − p(f)) / Δt
//     - {type: on_line, agent: 12, frames: [0, 60], point: [0, 0], direction: [1, 0]}
//     - {type: acceleration, agent: 12, frame: 50, acceleration: [0, 0]}   # m/s², default [0, 0]: the
//                                     # three-point second difference over the frame times at f−1, f, f+1 (at the
//                                     # clip's first or last frame the three nearest: one-sided)
//     - {type: sum, agents: [1, 2, 3], weights: [0.5, 0.25, 0.25], frames: [0, 60], value: [10, 2]}
//                                     # Σ w_k p_k = value at every frame of the range; weights default 1/n (the
//                                     # centroid), value default the original's sum at each frame
//     - type: row                     # a user's own row: Σ coefficient · p(agent, frame)[axis] = value
//       terms:
//         - {agent: 12, frame: 40, axis: x, coefficient: 1}               # coefficient default 1
//         - {agent: 17, frame: 42, axis: y, coefficient: -2}
//       value: 1.5
//
// Everything here is job data: a malformed entry is a ConfigError (exit 2) naming the line. Entries that do not
// fit the input crowd (an unknown agent, an agent absent from part of the clip, a frame out of range) are
// ConfigErrors from the editor naming pins[k], drags[k], constraints[k] (constraints[k].terms[j].agent, ...),
// formation.edits[k] or formation.splits[k]; contradictory constraints and a singular system are NumericalErrors
// (exit 5). See throng/edit/edit.h for the method.
#pragma once

#include <throng/edit/runner.h>
#include <throng/io/job_file.h>

namespace throng::edit {

/// Reads and checks a whole job, then calls node.finish() (unknown keys are errors). ConfigError naming the line.
void read_job(const ConfigNode& node, Job& job);
/// The job with every option at its effective value (for --print-config and the output's provenance).
[[nodiscard]] YAML::Node effective_job(const Job& job);
/// Writes beside the report (edit/runner.h) in /parameters/throng/edit:
///   sample_frames   int64[S]   the input frames the graph sampled (the clip's frames are first..last)
///   left_out_ids    int64[L]   ids of agents absent from part of the clip (not edited: copied unchanged into
///                              the whole-crowd output, absent from a clip-only output)
void write_data(const h5::Group& record, const Run& run);

}  // namespace throng::edit
