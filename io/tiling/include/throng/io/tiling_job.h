// The tiling job (`throng tile JOB.yaml -o TILING.h5`, or a `tile` step of `throng run`), the tiling data stored
// under /parameters/throng/tiling, and reading it back for `throng check-tiling`.
//
// Job file (every key optional but region and library; defaults shown; metres, seconds, degrees):
//
//   region: {min: [0, 0], max: [12, 12], time: [0, 20], periodic: [false, false, false]}  # the box to fill;
//                                    # periodic axes (x, y, t) make a repeating tile
//   obstacles: [...]                 # static or moving: see throng/io/scene_config.h
//   library:
//     builtin: [locomotion, interaction]   # built-in patch names or groups (locomotion, interaction, group,
//                                          # boxes, all): see throng/tiling/library.h
//     builtin_options: {sample_rate: 10, radius: 0.25, walk_speed: 1.3, walk_duration: 2, wait_duration: 2,
//                       preference_per_character: 1}
//     real:                          # optional: patches built from recorded trajectories (throng/tiling/construct.h)
//       dataset: ../data/real/zara01 # recorded data in any format `throng import` reads (import_crowd.h: an
//                                    # ETH/UCY folder or obsmat.txt, frame-id-x-y, PeTrack, CSV, PedPy HDF5, a
//                                    # crowd file), relative to the job file's folder; the effective job and the
//                                    # provenance name the resolved path
//       fps: 25                      # how to read it, as import's keys (flags --fps --columns --units --credit):
//       columns: "frame=f,id=p,x=X,y=Y"  # fps where the data states no rate, a CSV's column map, the positions'
//       units: cm                    # unit, a credit added to the data's own (absent: the format's own)
//       credit: "..."
//       sample_rate: 10              # and every RealPatchOptions field: max_gap, radius, standing_speed,
//       near: 1.5                    # clean_acceleration, min_contact, margin, reaction_min, synchronicity_min,
//       max_pair_patches: 20         # single_duration, max_single_patches, preference_per_character
//     preferences: {meet: 3}         # per type name: the phase-1 sampling weight (> 0), replaces the default
//   keyframes:                       # user-placed instances (§6 Keyframing): kept as placed, never removed
//     - {patch: bow_rows, position: [6, 6], angle: 0, time: 1.5}   # centroid, direction (deg), middle time;
//                                    # centroid and middle time inside the region (periodic axes wrap)
//   sources: [{center: [x, y], radius: 1, time: [t0, t1]}]   # entries here need no partner (time optional)
//   sinks:   [{center: [x, y], radius: 1, time: [t0, t1]}]   # exits here need no partner
//   characters: 0                    # phase 1 adds no patch beyond this many characters (0: no limit)
//   chains: 2                        # multi-start: independent chains, chain c seeded derive_seed(--seed, c)
//   preference:                      # Eq. 7, F = Π exp(−f_i / σ_i); absent terms are 1
//     position: {target: [x, y], sigma: 25}     # f1 = |p − target|² (m²), sigma σ1 in m²
//     direction: {target: 0, sigma: 40}         # f2 = (θ − target)², target in degrees, sigma σ2 in degrees²
//     time: {target: 10, sigma: 25}             # f3 = (t − target)² (s²)
//     labels: {friendly: 0, hostile: 2}         # f4 per label (absent: 0)
//     label_sigma: 1                            # σ4
//   limits: {stretch: 0.03, bend: 7, time_shift: 0.018, frame_rate: 30, bend_min_segment: 0.01,  # per frame
//            speed_ratio: 1.25}     # no deformed segment faster than this × the library's fastest (0 or ≥ 1; 0: none)
//   match: {distance: 1.0, angle: 25, time: 0.5}         # when an exit matches an entry
//   deformation: {anchor_weight: 0.001, deform_neighbours: true, constraint_tolerance: 1e-7}
//   annealing: {alpha: 0.2, k: 0.03, t_max: 200, t_step: 1, max_failures: 20000, max_proposals: 5000000}
//   search: {jitter_start: {distance: 0.6, angle: 15, time: 0.3}, jitter_end: {distance: 1.0, angle: 25, time: 0.5},
//            attempts: 12, max_steps: 400000}
//   index: {cell: 1.0, cell_time: 0.5}              # the space-time grid of the validity tests
//   obstacle_step: 0.1                              # obstacle tests every so many metres ...
//   obstacle_step_time: 0.05                        # ... and seconds along each path
//   output: {frame_rate: 10, repeat: [1, 1, 1],     # the characters' frames; copies of a repeating tile per axis
//            max_facing_rate: 270}                  # deg/s the facing turns at most; 0: the patches' headings
//
// Reading a job builds nothing (no dataset is imported, no patch made): the library is built when the job runs
// (throng/tiling/runner.h prepare()). Errors: what the file says (keys, ranges, unknown built-in patch names, a
// keyframe naming no built-in patch or placed outside the region) is a ConfigError with the line (exit 2) when the
// job is read; what needs the library (a keyframe naming no patch of a library with recorded patches, or of a patch
// that can never be used; resources beyond tile.h's limits: the deformation systems' memory, set by the sample
// rates and patch lengths, and the cells of the space-time index, set by index.cell, index.cell_time and the
// region) is a ConfigError naming the keys when it runs; a dataset that cannot be read is an IoError/InputError
// from the importer.
#pragma once

#include <throng/io/import_crowd.h>
#include <throng/io/job_file.h>
#include <throng/io/tiling_data.h>
#include <throng/tiling/runner.h>

#include <string>

namespace throng {

/// A parsed tiling job: the method's job (tiling/runner.h; the seed stays at its default: the command sets it
/// from --seed) and the recorded crowd its library takes patches from.
struct TilingJob : tiling::Job {
  std::string real_dataset;  ///< the resolved path of library.real.dataset (a file or a folder); empty: none
  ImportOptions real_import; ///< how import_crowd reads it: library.real's fps, columns, units, credit
};

/// The job's schema: the method's (tiling::describe) and library.real's reading options (describe_reading).
void describe(OptionBinder& b, TilingJob& job);

/// Reads and checks a whole job, then calls node.finish(). Imports nothing and builds nothing.
void read_job(const ConfigNode& node, TilingJob& job);

/// The job with every option at its effective value.
[[nodiscard]] YAML::Node effective_job(const TilingJob& job);

}  // namespace throng
