// The plausibility guard: a post-pass for any method's output that restores speed by a time warp and smooths
// kinks, given what the output was made from (Kwon et al. 2008 §6.2 use time warping after editing for the
// same reason: a deformed path walked in the old time is walked faster). Used by solver/stitch; edit and
// collide's outputs can go through it the same way.
//
// 1. Speed. The limit is max_speed_ratio × the source's fastest speed. Where some agent of the output is faster
//    (interval i needs a stretch n_i = its fastest speed / the limit > 1), one warp shared by every agent (as in
//    the paper: agents keep their pace relative to each other, so formations and contacts at frames are kept)
//    stretches the intervals: r_i = Δt′_i / Δt_i = 1 + max_k (n_k − 1) K((t_i − t_k) / σ), K(x) = (1 + |x|) e^{−|x|},
//    σ = ramp_time: r_i ≥ n_i, and the slow-down ramps in and out over about σ instead of jumping (a jump
//    would be a new kink). Every agent is then resampled at the output's frame rate through not-a-knot cubic
//    splines at the warped times (resample.h). Nothing needs stretching: the crowd is not resampled at all.
// 2. Kinks. A frame whose acceleration (central second difference) exceeds max(max_acceleration, the source's
//    own there) is a kink. Around each, the agent's positions over a window of ±smoothing_time (frames of one
//    run of presence) are replaced by the path of least squared second differences that joins the frames
//    outside it in position and velocity (two fixed frames each side; a window that reaches the end of the
//    agent's run is free there): the smoothest bridge across the kink, a cubic in time for uniform frames. A
//    window still holding a kink is widened by half, up to max_window_time; what is left is counted.
// The report says what acted. The source's accelerations are given per output frame (`Source`); a frame
// resampled by the warp takes the source's value at its unwarped time.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/report.h>
#include <throng/timewarp/timewarp.h>

#include <cstddef>
#include <vector>

namespace throng::timewarp {

struct GuardOptions {
  bool enabled = true;             ///< false: the output is left as it is (the paper's behaviour)
  double max_speed_ratio = 1.25;   ///< > 0: speed limit = this × the source's fastest speed
  double max_acceleration = 3.0;   ///< m/s² > 0: frames beyond this and beyond the source's own are kinks
  double ramp_time = 1.0;          ///< σ, seconds > 0: how the warp's slow-down ramps in and out
  double smoothing_time = 0.5;     ///< seconds > 0: first half-width of a kink's smoothing window
  double max_window_time = 2.0;    ///< seconds ≥ smoothing_time: the widest half-width tried
};

/// Throws ConfigError naming the option (prefix `what`, e.g. "guard").
void validate(const GuardOptions& options, const std::string& what = "guard");

/// What the output was made from, at the output's frames and agents.
///   max_speed     m/s: the source's fastest speed (> 0 for the speed limit to act)
///   acceleration  empty, or #frames × #agents (the output's, [T][N]) |a| of the source at that frame (m/s²; 0
///                 or NaN where unknown)
///   pinned_times  seconds, times of `output` whose positions the smoothing keeps (a formation's keyframes): the
///                 frame nearest each one's warped time is held where the warp put it
struct Source {
  double max_speed = 0;
  std::vector<double> acceleration;
  std::vector<double> pinned_times;
};

/// The source as `reference` moves at `output`'s frames and agents: agents matched by id, frames by time within
/// `time_tolerance_s` (match_reference: InputError when one is missing). For outputs at the input's frames
/// (edit, collide).
[[nodiscard]] Source source_of(const CrowdMotion& output, const CrowdMotion& reference, double time_tolerance_s = 1e-6);

/// The fastest speed over consecutive present frames, and |a| per frame ([T][N], 0 where not defined).
[[nodiscard]] double fastest_speed(const CrowdMotion& crowd);
[[nodiscard]] std::vector<double> accelerations(const CrowdMotion& crowd);

struct GuardReport {
  bool warped = false;
  std::size_t stretched_intervals = 0;  ///< intervals of the input with r > 1
  double largest_stretch = 1;           ///< max r
  double speed_limit = 0;               ///< m/s (0: none)
  double max_speed_before = 0, max_speed_after = 0;
  double duration_before = 0, duration_after = 0;  ///< seconds
  std::size_t kinks_before = 0;         ///< frames beyond the acceleration limit before smoothing (after the warp)
  std::size_t kinks_after = 0;          ///< and after
  std::size_t windows = 0;              ///< smoothing windows
  double largest_shift = 0;             ///< metres: the largest move of a position by the smoothing
  double max_acceleration_before = 0, max_acceleration_after = 0;  ///< m/s², over the whole crowd
};

struct GuardResult {
  CrowdMotion crowd;  ///< velocities dropped when anything changed
  Warp warp;          ///< identity (warped = source times) when not warped
  GuardReport report;
};

/// The report's guard fields, the same for every command that guards its output (stitch, edit, timewarp,
/// formation): guard_warped, guard_largest_stretch, guard_kinks_before, guard_kinks_after, guard_max_speed_m_s,
/// guard_max_acceleration_m_s2.
void describe(ReportWriter& w, const GuardReport& report);

/// Guards `output` (see above). Throws InputError when `source`'s acceleration has the wrong size.
[[nodiscard]] GuardResult guard(const CrowdMotion& output, const Source& source, const GuardOptions& options);

}  // namespace throng::timewarp
