// Every parameter of the tiler, with the paper's constants as defaults (seed 004 §5–6, METHODS.md §4).
// Units: metres, seconds, radians (the job file takes degrees where it says so).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace throng::tiling {

/// How far a patch may deform, per frame of the paper's 30 Hz motion data (§5.1: "positional stretching of
/// 3 cm, bending of 7 degrees, and time shifting of 0.018 second per frame"). Our patches are sampled more
/// coarsely; a sample interval of Δt seconds counts as n = Δt / frame_period_s frames, and the limits scale
/// with n (stretch and time shift add up over frames; bend is a rate of turning, n averaged over the two
/// intervals at a sample). Measured against the undeformed patch, so they do not depend on the placement:
///   stretch  | |p'_{i+1} − p'_i| − |p_{i+1} − p_i| |           ≤ stretch_m · n_i
///   time     | (t'_{i+1} − t'_i) − (t_{i+1} − t_i) |             ≤ time_shift_s · n_i
///   bend     | turn'_i − turn_i |  (turn = signed angle between consecutive segments)
///                                                               ≤ bend_rad · (n_{i−1} + n_i) / 2
/// Bend is measured only where all four segments are longer than `bend_min_segment_m` (a standing character has
/// no direction of travel to bend).
/// Beyond the paper: these per-frame limits let a walk at 1.3 m/s stretch to 2.2 m/s and, with the time shift,
/// to over 4 m/s (measured: 3.6 m/s on the shipped configs), so a deformed segment is also held to
///   speed    |p'_{i+1} − p'_i| / (t'_{i+1} − t'_i)                 ≤ speed_ratio · (fastest segment of the library)
/// the library being the crowd's input, as check-motion's speed limit reads it; speed_ratio = 0 drops this limit.
struct DeformationLimits {
  double stretch_m = 0.03;
  double bend_rad = 7.0 * std::numbers::pi / 180.0;
  double time_shift_s = 0.018;
  double frame_period_s = 1.0 / 30.0;
  double bend_min_segment_m = 0.01;
  double speed_ratio = 1.25;
};

/// When an exit matches an entry (§3 "within user-provided thresholds"; the paper does not give them: by
/// default the largest jitter of phase 2, the deformation the search itself asks patches to absorb).
/// Pose classes must be equal.
struct MatchThresholds {
  double distance_m = 1.0;
  double angle_rad = 25.0 * std::numbers::pi / 180.0;
  double time_s = 0.5;
};

/// Patch deformation (deformation.h): Laplacian path editing with handles and interpersonal constraints.
struct DeformationOptions {
  /// Weight of the term holding every sample near where the placement put it (relative to the Laplacian
  /// terms, weight 1). Small: a pulled patch bends and stretches as an elastic string; it only removes the
  /// patch's free similarity motions, so the system is always positive definite.
  double anchor_weight = 1e-3;
  /// The paper deforms the new instance and the instances it connects to (all others stay pinned, §5.1).
  /// false: only the new instance deforms (the paper's interactive variant, §5.3).
  bool deform_neighbours = true;
  /// A joint solve whose stitching constraints are met worse than this (metres or seconds) is rejected
  /// (the constraints contradicted each other).
  double constraint_tolerance = 1e-7;
};

/// Phase 1: simulated-annealing sampling (Algorithm 1, Eq. 6).
struct AnnealingOptions {
  double alpha = 0.2;            ///< α of Eq. 6: balances density against dangling ends
  double boltzmann_k = 0.03;     ///< k of the acceptance e^(−ΔE / kT)
  double t_max = 200.0;          ///< T_max: the starting temperature
  double t_step = 1.0;           ///< ΔT: T falls by this at every proposal; at T ≤ 0 only ΔE ≤ 0 is accepted
  std::size_t max_failures = 20000;    ///< i_max: stop after this many proposals in a row are not accepted
  std::size_t max_proposals = 5000000; ///< cap on proposals in all (no hang)
};

/// Phase 2: deterministic search with jittering and removal (Algorithm 2).
struct SearchOptions {
  /// Jitter range (§5.2): a disc of this radius, ± this angle, ± this time, growing linearly over the
  /// attempts from the first to the last value.
  double jitter_distance_start_m = 0.6;
  double jitter_distance_end_m = 1.0;
  double jitter_angle_start_rad = 15.0 * std::numbers::pi / 180.0;
  double jitter_angle_end_rad = 25.0 * std::numbers::pi / 180.0;
  double jitter_time_start_s = 0.3;
  double jitter_time_end_s = 0.5;
  std::size_t jitter_attempts = 12;   ///< i_max of Algorithm 2: placements tried per candidate (the first unjittered)
  /// Bridge candidates (search.cpp) tried per dangling end before Algorithm 2's own: patches that would join
  /// it to another dangling end at once. 0: the paper's search alone.
  std::size_t bridge_attempts = 8;
  /// On a tile periodic on every axis: sweeps in a row without fewer dangling ends before an open character is
  /// dropped (search.cpp).
  std::size_t stale_sweeps = 3;
  std::size_t max_steps = 400000;     ///< cap on candidate placements tried in all; reaching it ends the search
  /// On a tile periodic on every axis: a chain whose phase 2 has not closed every loop within restart_steps
  /// placements starts again from an empty tile with the next seed of its stream, at most `restarts` times; the
  /// attempt with the fewest dangling ends is kept (chain.cpp). 0 restarts: one attempt of max_steps.
  std::size_t restart_steps = 20000;
  std::size_t restarts = 8;
};

/// The preference function F = Π exp(−f_i / σ_i) (Eq. 7) over an instance's position (its centroid), direction
/// (its mean travel direction), time (the middle of its time span) and label. Absent terms are 1. It is the
/// sampling law of phase 1 and the candidate order of phase 2 (§5.3).
struct Preference {
  struct Position {
    Eigen::Vector2d target{0, 0};
    double sigma_m2 = 25.0;  ///< f1 = |p − target|², F1 = exp(−f1 / σ1)
  };
  struct Direction {
    double target_rad = 0.0;
    double sigma_rad2 = 0.5;  ///< f2 = wrap(θ − target)², wrap to (−π, π]
  };
  struct Time {
    double target_s = 0.0;
    double sigma_s2 = 25.0;  ///< f3 = (t − target)²
  };
  std::optional<Position> position;
  std::optional<Direction> direction;
  std::optional<Time> time;
  std::map<std::string, double> label_costs;  ///< f4(l) by label (absent labels cost 0)
  double label_sigma = 1.0;                   ///< σ4

  [[nodiscard]] bool empty() const noexcept {
    return !position && !direction && !time && label_costs.empty();
  }
};

/// The space-time index of character paths (the paper's bottleneck: "more than half of the computation time is
/// spent for bounding box tests"). A uniform grid over (x, y, t); cells are adjusted to divide periodic axes.
struct IndexOptions {
  double cell_m = 1.0;
  double cell_s = 0.5;
};

/// A part of the region with its own density (an axis-aligned box in the tile's coordinates).
struct DensityZone {
  Eigen::Vector2d min{0, 0};
  Eigen::Vector2d max{0, 0};
  double per_m2 = 0.0;  ///< characters per m² of the zone's area (free area when DensityOptions::free_area)
};

/// Density per area (presence.h, density.h): how many characters are inside an area at every time of the
/// horizon. The count at time t is the number of characters whose position at t lies in the area (characters
/// present by the region rule: a chain before its first entry or after its last exit is absent); the target
/// is per_m2 × area. Measured continuously over bins of `bin_s` seconds (the mean count in the bin) and
/// reported per window of `report_window_s` (mean, lowest and highest bin); a run meets its density when every
/// reported window's mean lies within ±tolerance of the target (relative).
struct DensityOptions {
  /// Characters per m² over the whole region (its box area, or free area); 0: no density for the region.
  double per_m2 = 0.0;
  /// Parts of the region with their own density, controlled and reported besides the region's own (if any).
  std::vector<DensityZone> zones;
  /// Areas exclude what obstacles cover (sampled on a raster of `area_cell_m`, at each bin's middle time for
  /// moving obstacles); false: the box area.
  bool free_area = false;
  double area_cell_m = 0.1;
  double tolerance = 0.1;        ///< relative, on each reported window's mean
  double bin_s = 2.0;            ///< control and measurement bins
  double report_window_s = 60.0; ///< reported windows (the run's windows when it is windowed)
  /// Correction rounds after phase 2 (chain.cpp): over-full bins lose whole removable groups of patches,
  /// under-full bins are sampled again (phase 1 then phase 2). 0: phase 1's cap alone.
  std::size_t rounds = 4;
  /// Walking speed (m/s) at which a dangling end is projected to the region's side (presence.h).
  double projection_speed_mps = 1.3;

  [[nodiscard]] bool enabled() const noexcept { return per_m2 > 0 || !zones.empty(); }
};

struct Options {
  DeformationLimits limits;
  MatchThresholds match;
  DeformationOptions deformation;
  AnnealingOptions annealing;
  SearchOptions search;
  Preference preference;
  IndexOptions index;

  /// Phase 1 adds no patch that would make the tiling hold more characters (chains of connected character
  /// fragments) than this; 0: no limit (phase 1 fills until i_max proposals in a row fail). The paper's
  /// Figure 7 rows differ by this density.
  std::size_t characters = 0;
  /// Density per area, met at every time within a tolerance (see DensityOptions); off by default. Both this and
  /// `characters` may be given: both caps then hold in phase 1.
  DensityOptions density;
  /// Obstacle tests sample each path segment at points at most obstacle_step_m apart in space and
  /// obstacle_step_s apart in time, and at every sample (moving obstacles are tested at the sample's time; on a
  /// periodic time axis at that time wrapped into the region).
  double obstacle_step_m = 0.1;
  double obstacle_step_s = 0.05;
  /// Multi-start: independent chains, chain c seeded derive_seed(seed, c), run on threads and MPI ranks
  /// (chain c on rank c mod size). The best is kept: fewest dangling ends, then the density per area (bins
  /// closest to their band, ChainReport::density_distance), then the character rule (closest to `characters`
  /// when set, else most characters), then the best mean preference, then the lowest chain index.
  std::size_t chains = 2;
  std::uint64_t seed = 1;
};

/// Throws ConfigError naming the first option with an impossible value, its value and what is expected.
void validate(const Options& options);

}  // namespace throng::tiling
