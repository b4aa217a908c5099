// Patch construction from recorded trajectories (paper §4, read with METHODS.md §4 "Beyond": root paths only).
//
//   1. Every agent's present span is resampled at `sample_rate_hz` (linear between recorded frames; a gap longer
//      than `max_gap_s` splits the span). Its state per sample: speed and heading (of the velocity; held while
//      standing).
//   2. Pose classes: two clusters of the state, "standing" (speed < standing_speed_mps) and "walking". A boundary
//      (entry or exit) may only fall on a *clean* sample, one whose state lies near its cluster's centre: standing
//      below standing_speed / 3, or walking with a speed change under clean_acceleration_mps2 — "frames whose
//      states fall in few clusters".
//   3. Episodes (interaction patches): two agents closer than near_m for at least min_contact_s. The episode is
//      the contact interval widened by margin_s on each side, each agent's fragment then moved to its nearest
//      clean samples. It is kept when it is interesting: reaction (Eq. 4 on velocity: the mean change of velocity
//      per second over the episode) at least reaction_min_mps2, or synchronicity (Eq. 5 with heading as gaze:
//      mean cos of the angle between each agent's heading and the direction to the other) at least
//      synchronicity_min. An interpersonal constraint ties the two at their closest approach (and at the
//      contact's ends).
//   4. Single-character patches: each span cut into pieces of about single_duration_s between clean samples,
//      kept at most max_single_patches, spread over the data (every k-th piece).
// Names: "<prefix>pair_<k>", "<prefix>single_<k>"; labels "pair" and "single". Frames are canonical
// (normalise_frames). Preference: characters × preference_per_character.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/tiling/patch.h>

#include <cstddef>
#include <string>

namespace throng::tiling {

struct RealPatchOptions {
  double sample_rate_hz = 10.0;
  double max_gap_s = 1.0;
  double radius_m = 0.25;
  double standing_speed_mps = 0.3;
  double clean_acceleration_mps2 = 0.6;
  double near_m = 1.5;
  double min_contact_s = 0.8;
  double margin_s = 1.0;
  double reaction_min_mps2 = 0.15;
  double synchronicity_min = 0.5;
  double single_duration_s = 3.0;
  std::size_t max_pair_patches = 20;
  std::size_t max_single_patches = 20;
  double preference_per_character = 1.0;
  std::string prefix = "real_";
};

/// Patches from recorded trajectories (see the file comment). Throws ConfigError for impossible options and
/// InputError when the data give no patch at all (naming what was missing).
[[nodiscard]] PatchLibrary patches_from_trajectories(const CrowdMotion& motion, const RealPatchOptions& options);

/// Adds `more`'s types to `into`, mapping pose classes by name. ConfigError when a type name is taken.
void merge_into(PatchLibrary& into, const PatchLibrary& more);

}  // namespace throng::tiling
