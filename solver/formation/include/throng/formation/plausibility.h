// The plausibility guard of a formation (issue 14; formation.h step 14): the spectral paths are timed by the
// keyframes alone, and a Catmull-Rom segment peaks at about 1.4 to 2 times the straight-line speed its keyframes
// ask for (measured on the shipped configs), with the accelerations of a sprint in the quick ones. The guard of
// solver/timewarp (guard.h) slows the whole formation down where some individual is faster than
// guard.max_speed_ratio × the stated speed, and smooths the frames whose acceleration exceeds guard.max_acceleration:
//
//   stated speed   Options::max_speed_mps when given (> 0); otherwise the keyframes' own: the fastest straight-line
//                  speed any individual needs between two consecutive keyframes, |p_k+1 − p_k| / (t_k+1 − t_k)
//   keyframes      the warp moves them later where it stretches time; Result::keyframe_frames are their new frames
//                  (the frame nearest each keyframe's warped time) and Result::guard says what acted
//
// The facings and actions travel with the resampled frames (slerp, the sample at or before). Deterministic.
// animate_formation is the paper's method and times the paths by the keyframes exactly; the formation job (runner.h:
// `throng formation`, the pipeline's formation step) applies this guard after it, by default.
#pragma once

#include <throng/formation/formation.h>

namespace throng::formation {

/// The fastest straight-line speed between consecutive keyframes over every individual of `motion` (m/s; 0 with
/// fewer than two keyframes). `keyframe_frames`: each keyframe's frame in `motion`.
[[nodiscard]] double keyframe_speed(const CrowdMotion& motion, const std::vector<std::size_t>& keyframe_frames);

/// Applies the guard to result.motion (when options.guard.enabled) and updates result.keyframe_frames and
/// result.guard.
void guard_formation(Result& result, const Options& options);

}  // namespace throng::formation
