// The plausibility guard after an edit (issue 14; throng/timewarp/guard.h): a drag that deforms a path walked
// in the old time makes it faster (Kwon et al. 2008 §6.2 time-warp after editing for this reason), and the
// edges of a drag's range bend the paths within a few frames (kinks). The guard runs on the crowd the edit
// writes (the whole crowd with the clip put back, or the clip alone), with the input at the same frames as the
// source: speed held to max_speed_ratio × the input's fastest speed (one time warp shared by every agent) and
// frames whose acceleration exceeds max(max_acceleration, the input's own there) smoothed.
//
// What the edit asked holds on every frame it covers, where the guard does not warp: the frames of every pin,
// drag range, velocity constraint (both frames of its difference), acceleration constraint (its three frames),
// row (every frame a term names) and relative-position, on-line or sum range are pinned (the smoothing keeps
// every agent's position there, GuardSource::pinned_times; a pinned frame is held for every agent, the guard
// pins frames, not vertices). Where the guard warps, the constraints hold at the warped
// times of their frames (the warp re-times the positions, the frame nearest each warped time is held), not at the
// output's frames of the same index, and a velocity constraint is slowed down with the rest.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/edit/edit.h>
#include <throng/timewarp/guard.h>

#include <cstddef>
#include <vector>

namespace throng::edit {

/// The input frames (sorted, unique) that `request` constrains within the clip [first_frame, last_frame]: pin
/// frames, every frame of a drag's range, a velocity's two frames, an acceleration's three (f − 1, f, f + 1, or
/// the three nearest at the clip's ends), every frame a row's terms name, every frame of a relative-position,
/// on-line or sum range (negative frames count back from last_frame, ranges are clamped to the clip, as the editor reads them).
[[nodiscard]] std::vector<std::size_t> constrained_frames(const Request& request, std::size_t first_frame,
                                                          std::size_t last_frame);

/// Guards `written`, the crowd an edit writes, whose frame k is input frame `written_first_frame` + k (0 for the
/// whole crowd, the clip's first frame for the clip alone); `input` is the edit's input crowd (agents matched by
/// id). The constrained frames of `request` (clip [first_frame, last_frame]) are pinned. Facing and actions are
/// resampled with the positions by a warp. options.enabled = false: `written` unchanged.
[[nodiscard]] timewarp::GuardResult guard_edit(const CrowdMotion& written, std::size_t written_first_frame,
                                               const CrowdMotion& input, const Request& request,
                                               std::size_t first_frame, std::size_t last_frame,
                                               const timewarp::GuardOptions& options);

/// The clip of `written` (as guard_edit's): frames first_frame..last_frame (input frames) of the agents with
/// `clip_ids`, positions and times only, for max_request_residual. Throws std::invalid_argument when it does not fit.
[[nodiscard]] CrowdMotion clip_of(const CrowdMotion& written, std::size_t written_first_frame, std::size_t first_frame,
                                  std::size_t last_frame, const std::vector<std::int64_t>& clip_ids);

}  // namespace throng::edit
