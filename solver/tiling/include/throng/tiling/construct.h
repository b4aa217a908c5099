// Patch construction from recorded trajectories (paper §4, read with METHODS.md §4 "Beyond": root paths only).
//
//   1. Every agent's present span is resampled at `sample_rate_hz` (linear between recorded frames; a gap longer
//      than `max_gap_s` splits the span into tracks). Its state per sample: velocity (central differences),
//      speed, heading (of the velocity; held while standing) and signed turn rate (of the heading).
//   2. Motion variation, Eq. 4 as written with the velocity as the "pose": V_i = Σ_{j=−w..w} Σ_{k=j+1..w}
//      ‖v_{i+j} − v_{i+k}‖² (m²/s²), w = round(reaction_window_s × sample_rate_hz), the window clamped at a
//      track's ends (the sum runs over the samples there are). See motion_variation().
//   3. Events of two agents A, B at a common sample (paper §4.1):
//        contact       distance < contact_m;
//        proximity     distance < near_m and V^A ≥ reaction_min or V^B ≥ reaction_min (m²/s²);
//        synchronicity distance < sync_range_m and S ≥ synchronicity_min, S of Eq. 5 as written with the heading
//                      as gaze (see synchronicity(); (m²/s²)²).
//      Consecutive event samples of a pair form an event; one lasting at least min_contact_s is kept.
//   4. Merging (the paper: events "nearby spatially and temporally" become one larger event): two events are
//      joined (union-find) when their time intervals overlap or are at most merge_gap_s apart, and they share
//      an agent or one agent of each comes within merge_distance_m of the other at a sample of the overlap (of
//      the gap between them when they do not overlap). An episode is the agents and the union interval of its
//      events. One of more than max_episode_characters characters is dropped (RealPatchReport counts it).
//   5. Boundaries (§4.2). Candidates are *clean* samples, whose state lies near a cluster's centre: standing
//      below standing_speed / 3, or walking with a change of velocity under clean_acceleration_mps2. Their
//      "poses" — (speed / pose_speed_scale_mps, turn rate / pose_turn_scale_radps) — are clustered by
//      agglomerative hierarchical clustering with complete linkage until the next merge would give a group of
//      diameter ≥ pose_threshold. To stay fast on tens of thousands of samples, the states are first binned at
//      a quarter of the threshold and the bins clustered with their distance bounded from above (centre
//      distance + a bin's diagonal), so a group's true diameter stays below the threshold. The pose_groups
//      largest groups (by samples) are the candidates. Every non-empty subset of them is scored by
//          diversity_weight × |subset| + (frames of all episode fragments) / (frames of all tracks),
//      each fragment of an episode running from the latest sample at least boundary_lead_s before the episode's
//      start to the earliest at least boundary_lead_s after its end that is clean and in a group of the subset,
//      searched within margin_s more.
//      Decided here, where the paper is silent or does not fit root data:
//      - boundary_lead_s departs from the paper's tight boundaries (0 gives them): on zara01 tight boundaries
//        make episode patches of about 1 s, too short to absorb the deformation a stitch needs — the
//        8 × 8 m × 8 s tiling of tests/tiling/test_tiling_job.cpp then kept 27 to 57 dangling ends, with 1 s
//        none (seeds 1–3). The price: fewer episodes find a boundary inside short tracks (zara01 keeps 15 of 31
//        instead of 22, hotel 7 of 61 instead of 22).
//      - An episode with no such boundary for some agent is dropped under that subset, and it costs the frames
//        of its agents' whole tracks (as if the boundary search ran on to the tracks' ends): dropping is paid
//        for like a very long patch, and only a large weight prefers it to one more group.
//      - Single pieces do not enter the score (their length is fixed by single_duration_s).
//      - Ties go to the lowest bit mask (bit g for the g-th largest group).
//   6. Pose classes: each chosen group is a pose class "<prefix>pose_<g>" (g its rank by size), or, with
//      builtin_classes, "standing" when its centre speed < standing_speed_mps else "walking" (the built-in
//      locomotion patches' classes; groups may share a name — entries and exits match by name).
//   7. Patches: each episode kept becomes "<prefix>pair_<k>" (label "pair") or, with 3+ characters,
//      "<prefix>group_<k>" (label "group"); at most max_episode_patches, the earliest first (measured on the
//      zara01 tiling test: taking the shortest or the largest episodes first left dangling ends). Every pair of
//      the episode that had an event is tied (InterpersonalConstraint) at its closest approach over its events;
//      people merged only by coming near each other's events are not tied to each other. Single-character
//      pieces ("<prefix>single_<k>", label "single"): each track cut into pieces of about single_duration_s
//      between boundary samples of the chosen groups, at most max_single_patches, spread over the data (every
//      k-th piece).
// Frames are canonical (normalise_frames). Preference: characters × preference_per_character.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/tiling/patch.h>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace throng::tiling {

struct RealPatchOptions {
  double sample_rate_hz = 10.0;
  double max_gap_s = 1.0;
  double radius_m = 0.25;
  double standing_speed_mps = 0.3;
  double clean_acceleration_mps2 = 0.6;
  double reaction_window_s = 0.5;     ///< half window of Eq. 4
  double contact_m = 0.6;
  double near_m = 1.5;
  /// Eq. 4 threshold of a reaction (m²/s²). A change of velocity Δ spread evenly over the 1 s window gives
  /// V ≈ 12·Δ², so 2 is a change of about 0.4 m/s within a second (a 20° turn at 1.2 m/s, or slowing by a third).
  /// Measured at 10 Hz with a 0.5 s window, V over all samples: zara01 median 0.15, 90th percentile 1.9 (2 is
  /// its ~88th); hotel median 1.25, 90th 5.6; eth median 2.2 (noisy tracking), univ_students03 median 2.4.
  double reaction_min_m2ps2 = 2.0;
  double sync_range_m = 4.0;
  /// Eq. 5 threshold ((m²/s²)²): both reacting at reaction_min while facing each other (2 × 2 × e⁰ × e⁰).
  /// Measured S of pairs within sync_range: zara01 99th percentile 1.2, hotel 95th 2.4, eth 90th 4.7.
  double synchronicity_min = 4.0;
  double min_contact_s = 0.8;
  double merge_gap_s = 1.0;
  double merge_distance_m = 2.0;
  std::size_t max_episode_characters = 6;
  double margin_s = 1.0;
  double boundary_lead_s = 1.0;       ///< boundaries at least this far from an episode (see step 5)
  /// Boundary pose distance units: a group spans less than 0.5 m/s and 1 rad/s. Measured (defaults otherwise):
  /// 0.6 times these kept fewer episodes (zara01 14 instead of 15, hotel 2 instead of 7, eth 12 instead of 13).
  double pose_speed_scale_mps = 0.5;
  double pose_turn_scale_radps = 1.0;
  double pose_threshold = 1.0;
  std::size_t pose_groups = 10;   ///< k of §4.2 (the paper's typical value); at most 16
  /// Measured (defaults otherwise): at 0.003 zara01, hotel, eth and univ_students03 keep as many episodes as
  /// with every group allowed (weight 0: 15, 7, 13, 1) from 7, 7, 4 and 1 groups of 10; at 0.01 hotel keeps 1,
  /// at 0.03 zara01 11 and eth 3.
  double diversity_weight = 0.003;
  bool builtin_classes = true;
  double single_duration_s = 3.0;
  std::size_t max_episode_patches = 20;
  std::size_t max_single_patches = 20;
  double preference_per_character = 1.0;
  std::string prefix = "real_";
};

/// What patches_from_trajectories found.
struct RealPatchReport {
  std::size_t episodes = 0;              ///< after merging, before any was dropped
  std::size_t pairs = 0;                 ///< episode patches made, by characters: 2
  std::size_t groups_of_3 = 0;           ///< 3
  std::size_t groups_of_4_plus = 0;      ///< 4 or more
  std::size_t dropped_too_large = 0;     ///< more than max_episode_characters
  std::size_t dropped_no_boundary = 0;   ///< no boundary in the chosen groups for some agent
  std::size_t dropped_over_cap = 0;      ///< beyond max_episode_patches
  std::vector<std::string> chosen_classes;  ///< the pose class of each chosen group, largest group first
};

/// Eq. 4 for every sample of one track: V_i = Σ_{j=−w}^{w} Σ_{k=j+1}^{w} ‖v_{i+j} − v_{i+k}‖², the window clamped
/// at the ends (only the indices inside [0, n) take part).
[[nodiscard]] std::vector<double> motion_variation(const std::vector<Eigen::Vector2d>& velocities, std::size_t w);

/// Eq. 5 for two concurrent samples: V^A · V^B · e^{−g(A,B)} · e^{−g(B,A)}, g(A,B) the angle in [0, π] between A's
/// heading and the vector from A to B (0 when they coincide).
[[nodiscard]] double synchronicity(double variation_a, double variation_b, const Eigen::Vector2d& position_a, double heading_a,
                                   const Eigen::Vector2d& position_b, double heading_b);

/// Patches from recorded trajectories (see the file comment); `report`, when given, says what was found. Throws
/// ConfigError naming the key of an impossible option and InputError when the data give no patch at all.
[[nodiscard]] PatchLibrary patches_from_trajectories(const CrowdMotion& motion, const RealPatchOptions& options,
                                                     RealPatchReport* report = nullptr);

/// Adds `more`'s types to `into`, mapping pose classes by name. ConfigError when a type name is taken.
void merge_into(PatchLibrary& into, const PatchLibrary& more);

}  // namespace throng::tiling
