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
//       dataset: data/real/zara01   # a dataset folder (relative: to the job file, else the working
//                                    # dir); the effective job and the provenance name the resolved folder
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
//   limits: {stretch: 0.03, bend: 7, time_shift: 0.018, frame_rate: 30, bend_min_segment: 0.01}  # per frame
//   match: {distance: 1.0, angle: 25, time: 0.5}         # when an exit matches an entry
//   deformation: {anchor_weight: 0.001, deform_neighbours: true, constraint_tolerance: 1e-7}
//   annealing: {alpha: 0.2, k: 0.03, t_max: 200, t_step: 1, max_failures: 20000, max_proposals: 5000000}
//   search: {jitter_start: {distance: 0.6, angle: 15, time: 0.3}, jitter_end: {distance: 1.0, angle: 25, time: 0.5},
//            attempts: 12, max_steps: 400000}
//   index: {cell: 1.0, cell_time: 0.5}              # the space-time grid of the validity tests
//   obstacle_step: 0.1                              # obstacle tests every so many metres ...
//   obstacle_step_time: 0.05                        # ... and seconds along each path
//   output: {frame_rate: 10, repeat: [1, 1, 1]}     # the characters' frames; copies of a repeating tile per axis
//
// Errors: everything in the job (keys, ranges, unknown patch names, a keyframe naming no patch or placed outside
// the region or of a patch that can never be used, resources beyond tile.h's limits: the deformation systems'
// memory, set by the sample rates and patch lengths, and the cells of the space-time index, set by index.cell,
// index.cell_time and the region) is a ConfigError with the line (exit 2); a dataset that cannot be read is an
// IoError/InputError from the importer.
#pragma once

#include <throng/core/scene.h>
#include <throng/io/config.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>
#include <throng/tiling/characters.h>
#include <throng/tiling/check.h>
#include <throng/tiling/construct.h>
#include <throng/tiling/library.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tile.h>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace throng {

/// A parsed tiling job (the seed stays at its default: the command sets it from --seed).
struct TilingJob {
  tiling::PatchLibrary library;
  tiling::Environment environment;
  std::vector<tiling::Keyframe> keyframes;
  tiling::Options options;
  tiling::LayoutOptions layout;
  // What the library was made from, for the effective job.
  std::vector<std::string> builtin;
  tiling::BuiltinOptions builtin_options;
  std::string real_dataset;          ///< the resolved dataset folder; empty: none
  tiling::RealPatchOptions real_options;
  std::vector<std::pair<std::string, double>> preferences;
  std::vector<std::string> credits;  ///< credit lines of the real data used
};

/// Reads and checks a whole job (building the library), then calls job.finish().
[[nodiscard]] TilingJob read_tiling_job(const ConfigNode& job);

/// The job with every option at its effective value.
[[nodiscard]] YAML::Node effective_tiling_job(const TilingJob& job);

/// The check options that go with a job's tiler options (the same limits and thresholds).
[[nodiscard]] tiling::CheckOptions check_options_for(const tiling::Options& options);

/// The scene of the laid characters (the crowd file's scene): the region covers every laid copy (repeat[a]
/// periods along each periodic axis) and keeps the tile's periodic flags (the laid box repeats as the tile does);
/// obstacles are copied into every laid copy in space (the tile's own first, then copy by copy, x-major).
/// Moving obstacles follow their motion once: a time copy of a periodic-time tile does not repeat it.
[[nodiscard]] Scene laid_scene(const tiling::Environment& environment, const tiling::LayoutOptions& layout);

/// Writes /parameters/throng/tiling:
///   library/pose_classes string[P]; library/type_name, type_label string[K]; library/type_preference float64[K];
///   library/type_fragments int64[K+1] (first fragment of each type); library/fragment int64[F][4] (kind 0
///   character 1 prop, entry class, exit class, first sample); library/fragment_radius float64[F];
///   library/samples float64[S+…][4] (x, y, heading, t in the type's canonical frame); library/constraints
///   int64[C][5] (type, fragment a, sample a, fragment b, sample b)
///   instances/type int64[I]; instances/transform float64[I][4] (x, y, angle rad, time shift);
///   instances/keyframed int32[I]; instances/paths float64[S'][4] (x, y, heading, t: every instance's fragments
///   in order, each with its type's sample count)
///   connections int64[C][7] (from instance, from fragment, to instance, to fragment, image x, y, t)
///   sources, sinks float64[n][5] (centre x, y, radius, t0, t1)
///   agents/pieces int64[P][6] (agent, instance, fragment, copy x, y, t): the fragments each output agent walks
///   region float64[6] (min x, min y, max x, max y, t0, t1) and region_periodic int32[3]: the tile (the crowd's
///   scene region is the laid extent, see laid_scene); repeat int64[3]: the copies laid per axis
///   attributes: the check options (limits, match, obstacle steps), tile_obstacles (how many of the scene's
///   obstacles, the first ones, are the tile's own) and the report (dangling, chains, best_chain, instances,
///   characters, connections). No wall time: the same seed gives the same file.
void write_tiling_data(const h5::Group& throng_parameters, const tiling::PatchLibrary& library,
                       const tiling::TilingResult& result, const tiling::Environment& environment,
                       const tiling::CheckOptions& check, const tiling::Characters& characters,
                       const tiling::LayoutOptions& layout);

/// What `throng check-tiling` and `throng plot` need from a tiling file.
struct TilingData {
  tiling::PatchLibrary library;
  tiling::Tiling tiling;
  tiling::Environment environment;  ///< the tile: its region, its own obstacles, sources and sinks
  tiling::CheckOptions check;
  std::array<int, 3> repeat{1, 1, 1};                   ///< copies laid per axis
  std::vector<std::vector<tiling::AgentPiece>> pieces;  ///< per output agent, the fragment copies it walks
};

/// Reads a crowd file written by `throng tile`. IoError (missing or unreadable), InputError (no tiling data,
/// bad shapes).
/// Bounded by `limits` as read_crowd_file is; indices and stored check options are range-checked (InputError).
[[nodiscard]] TilingData read_tiling_data(const std::filesystem::path& path, const ReadLimits& limits = {});

/// Whether a crowd file holds /parameters/throng/tiling. IoError when it cannot be opened.
[[nodiscard]] bool has_tiling_data(const std::filesystem::path& path, const ReadLimits& limits = {});

}  // namespace throng
