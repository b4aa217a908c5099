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
//       sample_rate: 10              # and every RealPatchOptions field (construct.h: episode detection by
//       near: 1.5                    # contact, proximity with reaction (Eq. 4) and synchronicity (Eq. 5), merged
//       max_episode_patches: 20      # into groups, boundaries from clustered poses): max_gap, radius,
//                                    # standing_speed, clean_acceleration, reaction_window, contact, reaction_min,
//                                    # sync_range, synchronicity_min, min_contact, merge_gap, merge_distance,
//                                    # max_episode_characters, margin, boundary_lead, pose_speed_scale,
//                                    # pose_turn_scale, pose_threshold, pose_groups, diversity_weight,
//                                    # builtin_classes, single_duration, max_single_patches,
//                                    # preference_per_character, prefix
//     file: ../shots/library.h5      # optional: the library of a file written by `throng tile` (built once, with
//                                    # its recorded patches, and reused by later jobs: every shot of a batch), relative
//                                    # to the job file's folder; its types come first, builtin and real add to them
//     preferences: {meet: 3}         # per type name: the phase-1 sampling weight (> 0), replaces the default
//   keyframes:                       # user-placed instances (§6 Keyframing): kept as placed, never removed
//     - {patch: bow_rows, position: [6, 6], angle: 0, time: 1.5}   # centroid, direction (deg), middle time;
//                                    # centroid and middle time inside the region (periodic axes wrap)
//   sources: [{center: [x, y], radius: 1, time: [t0, t1]}]   # entries here need no partner (time optional)
//   sinks:   [{center: [x, y], radius: 1, time: [t0, t1]}]   # exits here need no partner
//   characters: 0                    # phase 1 adds no patch beyond this many characters (0: no limit)
//   density:                         # characters per m² at every time of the horizon (tiling/options.h DensityOptions)
//     per_m2: 0                      # over the whole region (0: none); met per report window within tolerance
//     zones: [{min: [x, y], max: [x, y], per_m2: 0.1}]   # parts of the region with their own density
//     free_area: false               # areas are what obstacles leave free (sampled every area_cell metres)
//     area_cell: 0.1
//     tolerance: 0.1                 # relative, on each report window's mean
//     bin: 2                         # control and measurement bins (s)
//     report_window: 60              # reported windows (s; a windowed run reports its own windows)
//     rounds: 4                      # correction rounds after phase 2
//     projection_speed: 1.3          # m/s at which a dangling end is projected to the region's side
//   window: 0                        # > 0: tile the horizon window by window of this many seconds and stream the
//                                    # crowd to the output as it goes (`throng tile` only; --resume continues a
//                                    # stopped run; io/tiling_stream.h is the file's layout). Not with keyframes,
//                                    # output.repeat, a region periodic in time, or `characters`
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
  std::string library_file;  ///< the resolved path of library.file (a file written by `throng tile`); empty: none
  ImportOptions real_import; ///< how import_crowd reads it: library.real's fps, columns, units, credit
};

/// The job's schema: the method's (tiling::describe) and library.real's reading options (describe_reading).
void describe(OptionBinder& b, TilingJob& job);

/// Reads and checks a whole job, then calls node.finish(). Imports nothing and builds nothing.
void read_job(const ConfigNode& node, TilingJob& job);

/// The job with every option at its effective value.
[[nodiscard]] YAML::Node effective_job(const TilingJob& job);

}  // namespace throng
