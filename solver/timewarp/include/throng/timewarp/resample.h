// A crowd sampled at new times through per-agent cubic splines (throng/timewarp/spline.h): the last step of a
// time warp (paper §6.2), and the frame-rate change of a retimed clip.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/timewarp/spline.h>

#include <vector>

namespace throng::timewarp {

/// start, start + 1/rate, start + 2/rate, ... up to `end` (an output time within 1e-9 of the duration past `end`
/// counts as `end`). Throws ConfigError for a rate that is not positive and finite, InputError for end < start.
[[nodiscard]] std::vector<double> uniform_times(double start, double end, double rate_hz);

/// The input's frame rate: 1 / the median frame interval (Hz), snapped to whole mHz when within 1e-9 relative
/// (stored times k/24 give 23.99999999999983). InputError for fewer than 2 frames.
[[nodiscard]] double frame_rate(const CrowdMotion& crowd);

/// The crowd at `times`. Each agent's x, y and z pass through a cubic spline over `knot_times` (one knot per frame
/// of `crowd`: its own times, or warped ones) and are evaluated at `times`.
///   knot_times  #frames of crowd, strictly increasing;   times  #output frames, strictly increasing
/// Presence: one spline per run of consecutive frames where the agent is present (agents present throughout
/// share one fit); the agent is present at an output time inside a run's knot span widened by `end_slack_s` at
/// each end, but by less than half the knot interval towards a frame where the agent is absent (a run of a single
/// frame with no slack: only at that knot's time, within 1e-9 s). Outside the knot span the run's end value is
/// held (the spline is not extrapolated). A resampling to a new frame rate passes half the output interval, so an
/// agent's first and last samples land on the output frames nearest them instead of being dropped when the warp
/// moves them a little past a frame. Agents keep their order, ids, radii and species, also when they are present
/// at no output time. `with_velocities`: velocities are the splines' first derivatives (m/s per unit of `times`),
/// else none. Facing and actions, when the crowd has them: orientations slerp between the two frames around an
/// output time, the action is the one of the frame at or before it; the action table is kept. Deterministic
/// whatever the thread count. ConfigError for a negative or non-finite slack.
[[nodiscard]] CrowdMotion resample_crowd(const CrowdMotion& crowd, const std::vector<double>& knot_times,
                                         const std::vector<double>& times, SplineEnd end = SplineEnd::not_a_knot,
                                         bool with_velocities = false, double end_slack_s = 0.0);

}  // namespace throng::timewarp
