// Splitting a crowd (paper §3: "A group of characters can be divided into multiple groups ... A single group
// motion clip can be split into multiple clips in the time domain"): by time — the two halves share the frame
// where they are cut, so stitching them back gives t + t′ − 1 frames (§5) — and by agents.
//
// Both keep the data exactly (positions, velocities, ids, radii, species, times, and facing, actions and the
// action table when the crowd has them); the scene is the caller's
// business (both parts keep it). A part keeps only the agents present somewhere in it, unless the caller asks for
// the agents present throughout (a clip, as editing and stitching need).
#pragma once

#include <throng/core/crowd_motion.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace throng::stitch {

/// Frames first..last (inclusive) of `crowd`. Agents absent over the whole range are left out; with
/// `present_throughout`, so is every agent absent at some frame of it. Throws ConfigError for a range that is
/// reversed, shorter than 2 frames or past the crowd's last frame, InputError when no agent is left.
[[nodiscard]] CrowdMotion slice_frames(const CrowdMotion& crowd, std::size_t first, std::size_t last,
                                       bool present_throughout = false);

/// The two halves of a split at frame `frame`: frames 0..frame and frame..T−1 (both hold frame `frame`).
/// ConfigError unless 0 < frame < T − 1.
struct TimeSplit {
  CrowdMotion first;
  CrowdMotion second;
};
[[nodiscard]] TimeSplit split_at_frame(const CrowdMotion& crowd, std::size_t frame, bool present_throughout = false);

/// The frame whose time is nearest `time` (seconds; the earlier one on a tie). ConfigError when `time` lies more
/// than half a frame interval outside the crowd's times.
[[nodiscard]] std::size_t frame_nearest(const CrowdMotion& crowd, double time);

/// Agents chosen by id and by species: the union of both lists.
struct AgentSelection {
  std::vector<std::int64_t> ids;
  std::vector<std::int32_t> species;
};

/// Indices of the selected agents (increasing), or of the others when `complement`. Throws ConfigError for an
/// empty selection (both lists empty), an id that is not in the crowd, or a species no agent has (messages list
/// what the crowd has); an empty result (the complement of everybody) is an InputError.
[[nodiscard]] std::vector<std::size_t> select_agents(const CrowdMotion& crowd, const AgentSelection& selection,
                                                     bool complement = false);

/// The given agents (indices, any order; the result keeps that order) at every frame.
[[nodiscard]] CrowdMotion take_agents(const CrowdMotion& crowd, const std::vector<std::size_t>& agents);

}  // namespace throng::stitch
