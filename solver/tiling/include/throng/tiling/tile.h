// The tiler: fills a space-time region with deformable motion patches so that no entry or exit is left
// dangling (seed 004 §5, METHODS.md §4). A long horizon is tiled window by window by windowed.h.
//
//   tile()  validates the library, keyframes and options; finds the patch types that can ever be used inside
//           the region (pose classes that no end of the opposite kind ever has make a type unusable: when none
//           is usable, a NumericalError says why, before any search); precomputes each type's deformation
//           system; then runs `chains` independent chains (threads × MPI ranks), each:
//             keyframes (their characters continued by the phase-2 search while the region is empty) →
//             phase 1 (annealing, Algorithm 1, Eq. 6) → phase 2 (search, Algorithm 2) → density rounds,
//           and keeps the best chain (options.h: Options::chains). Every rank returns the same tiling.
//
// Decisions where the paper is unclear (see also options.h, deformation.h):
// - Algorithm 1 as printed (METHODS.md): i is reset on acceptance; T falls by ΔT at every proposal and stops at
//   0, after which only proposals that do not raise E_tiling are accepted. ΔE is computed on the stitched and
//   deformed tiling, before the validity test. N_c and N_d count ends (a connection is two connected ends);
//   ends that need no partner (tiling.h) count in neither.
// - A proposal is stitched to existing dangling ends of the opposite kind and the same pose class within the
//   match thresholds, each new end to at most one, greedily by normalised distance (ties: lowest instance,
//   fragment). Keyframes are placed first, never stitched to each other, never deformed or removed.
// - Phase 2 visits dangling ends in time order (then instance, fragment, entry before exit), places each
//   candidate so that its matching end lands exactly on the dangling end, tries it unjittered and then jittered
//   (the jitter range grows with the attempt), and requires every attempt not to raise the dangling count.
//   History: a removed instance's (type, fragment, anchor end) is never proposed again at that end.
//   Our additions (search.cpp, bridges.h): bridges, patches fitted between d and another dangling end to join
//   both at once, tried before removing d's patch (before the candidates on a tile periodic on every axis, where
//   no end can leave by a side); and on such a tile, after sweeps that lower nothing, the smallest connected
//   group of patches holding a dangling end is dropped whole (at most half the tiling; never a keyframe).
// - Loops (a tile periodic on x, y and t, where every character must close a loop; bridges.h, closure.cpp):
//   only exits are continued, each first by a planned way to a near dangling entry (a beam search over the
//   single-character patches, then a bridge), then by two-patch bridges, then by the candidates in order of how
//   well they keep to schedule for an entry; with a density per area phase 1 starts no more chains than the
//   target count and phase 2 raises no bin above (1 + tolerance) × target; a chain that has not closed every
//   loop within SearchOptions::restart_steps placements starts again with the next seed of its stream.
//   Perfect for 20 seeds of 20 on 10 m × 10 m × 20 s at 0.1 characters/m² (bench/tiling BM_LoopSeeds).
// - Validity: no two character or prop capsules of different instances closer than the sum of their radii at
//   any time (exact closest approach of the linearly interpolated paths, continuous in time), except the two
//   fragments a connection joins (the same character); no capsule closer to an obstacle than its radius at the
//   sampled points (Options::obstacle_step_m); deformation within the limits; times strictly increasing.
// - Periodic axes: every distance, match and collision uses the nearest image; instance translations and time
//   shifts are kept inside the tile.
// - Density per area (options.h DensityOptions; the paper sets density by counts of patches or characters):
//   phase 1 refuses a proposal that would raise the presence of an area in a time bin above its target,
//   counting what the patch's open ends will become when phase 2 continues them (projected straight on to the
//   region's side, presence.h); after phase 2, correction rounds drop whole groups of patches from over-full
//   bins and sample under-full ones again (density_control.cpp). measure_density (density.h) reports it.
#pragma once

#include <throng/core/progress.h>
#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace throng::tiling {

/// What tile() may allocate, checked before anything is (ConfigError beyond): the dense deformation systems of
/// every patch type (deformation.h: a type of n samples holds a 2n × 2n and an n × n matrix of doubles, 40 n²
/// bytes) and the cells of each chain's space-time grids (the segment index, options.h IndexOptions, and the
/// index of dangling ends, cells of the match distance and time) over the region and its margins.
inline constexpr double max_deformation_bytes = 2e9;
inline constexpr double max_index_cells = 1e7;

/// Bytes the deformation systems of `library` take (see max_deformation_bytes).
[[nodiscard]] double deformation_bytes(const PatchType& type);
/// Cells of the larger of a chain's two grids for this library, region and options (see max_index_cells).
[[nodiscard]] double index_cells(const PatchLibrary& library, const Region& region, const Options& options);

/// A user-placed instance (§6 "Keyframing"): part of the initial tiling, kept as placed.
struct Keyframe {
  std::size_t type = 0;
  Transform transform;
};

/// What a chain did.
struct ChainReport {
  std::size_t chain = 0;
  std::size_t dangling = 0;
  std::size_t instances = 0;
  std::size_t characters = 0;
  double mean_preference_cost = 0;  ///< mean over instances of Σ f_i / σ_i (lower is better)
  std::size_t proposals = 0;        ///< phase 1
  std::size_t accepted = 0;         ///< phase 1
  std::size_t phase1_instances = 0;
  std::size_t phase1_dangling = 0;
  std::size_t search_steps = 0;     ///< phase 2 candidate placements tried
  std::size_t removals = 0;         ///< phase 2
  double phase1_seconds = 0;
  double phase2_seconds = 0;
  bool search_capped = false;       ///< phase 2 stopped at SearchOptions::max_steps
  std::size_t attempts = 1;         ///< attempts made (more than one only on a tile periodic on every axis)
  std::size_t density_rounds = 0;   ///< correction rounds run for the density per area (options.h)
  std::size_t density_removed = 0;  ///< instances those rounds dropped from over-full bins
  /// How far the controlled density bins lie outside their tolerance band, in all, relative to the sum of their
  /// targets (0: every bin within its band; 0 without a density).
  double density_distance = 0;
};

struct TilingReport {
  std::vector<ChainReport> chains;  ///< every chain, by chain index
  std::size_t best_chain = 0;
  std::size_t dangling = 0;         ///< of the kept tiling: 0 means perfect
  std::size_t instances = 0;
  std::size_t characters = 0;
  std::size_t connections = 0;
  std::vector<std::size_t> unusable_types;  ///< types left out (an end nothing can ever match)
  double seconds = 0;               ///< wall time of tile() on this rank
  [[nodiscard]] bool perfect() const noexcept { return dangling == 0; }
};

struct TilingResult {
  Tiling tiling;
  TilingReport report;
};

/// Tiles `environment.scene.region` with instances of `library` (see the file comment). Throws ConfigError
/// (bad options, no region, resources beyond the limits above, a keyframe naming no type, placed with its
/// centroid or middle time outside the region, colliding, or with an end inside the region of a pose class no
/// usable type continues), InputError (an invalid library), and NumericalError when no patch type can ever be
/// placed without leaving a dangling end; all before any search. An imperfect result (caps reached, or a
/// search that stopped because nothing fits the ends left) is returned, not thrown: report.perfect() says.
/// Progress is reported from the calling thread.
/// MPI: when launched by mpiexec, every rank must call tile() with the same arguments.
[[nodiscard]] TilingResult tile(const PatchLibrary& library, const Environment& environment,
                                const std::vector<Keyframe>& keyframes, const Options& options, Progress& progress);

}  // namespace throng::tiling
