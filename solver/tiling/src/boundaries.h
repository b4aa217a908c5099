// Boundary determination (construct.h step 5): pose groups of the clean samples and the subset of them that
// balances diversity against compactness.
#pragma once

#include "episodes.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace throng::tiling {

/// A subset of the pose groups: bit g set when group g is chosen.
using GroupMask = std::uint32_t;

/// The largest pose groups (largest first), each sample's group written to Track::group.
struct PoseGroups {
  std::vector<double> centre_speed;   ///< m/s, mean over the group's samples
  std::vector<std::size_t> samples;   ///< its size
};

/// Clusters the clean samples of `tracks` (complete linkage under pose_threshold) and keeps the pose_groups
/// largest groups.
[[nodiscard]] PoseGroups cluster_poses(std::vector<Track>& tracks, const RealPatchOptions& o);

/// One agent's fragment of an episode: first and last local sample.
using Bounds = std::pair<std::size_t, std::size_t>;

/// The fragment of track `t` around `episode`: from the latest sample boundary_lead_s or more before its start to
/// the earliest boundary_lead_s or more after its end that is clean and in a group of `chosen`, within margin_s
/// more; nothing when there is none on either side.
[[nodiscard]] std::optional<Bounds> bound(const Track& t, const Episode& episode, GroupMask chosen, const RealPatchOptions& o);

/// The non-empty subset of `groups` groups with the least diversity_weight × |subset| + (episode frames) /
/// (track frames); see construct.h step 5 for dropped episodes and ties.
[[nodiscard]] GroupMask choose_groups(const std::vector<Episode>& episodes, const std::vector<Track>& tracks, std::size_t groups,
                                      const RealPatchOptions& o);

}  // namespace throng::tiling
