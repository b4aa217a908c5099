// The plausibility guard of a formation (issue 14, beyond the paper): the spectral paths are timed by the
// keyframes alone, and a Catmull-Rom interval peaks at about 1.4 to 2 times the straight-line speed its keyframes
// ask for (measured on the shipped configs), with the accelerations of a sprint in the quick ones. The guard
//
//   1. re-times the keyframes: where an individual is faster than guard.max_speed_ratio × the stated speed in an
//      interval, that interval is lengthened by the ratio (rounded up to whole frames, so every keyframe stays
//      on a frame) and the formation is made again with the new times (at most 4 rounds). The method itself is
//      unchanged: the same paths, walked more slowly where they were too fast; every keyframe is hit exactly.
//   2. smooths what is left beyond guard.max_acceleration (solver/timewarp guard.h step 2: the smoothest bridge
//      over a window round each kink), keyframe frames pinned.
//
//   stated speed   Options::max_speed_mps when given (> 0); otherwise the keyframes' own: the fastest straight-line
//                  speed any individual needs between two consecutive keyframes, |p_k+1 − p_k| / (t_k+1 − t_k)
//
// animate_formation is the paper's method with the job's times; the formation job (runner.h: `throng formation`,
// the pipeline's formation step) applies this guard after it, by default. Deterministic.
#pragma once

#include <throng/core/progress.h>
#include <throng/formation/formation.h>

namespace throng::formation {

/// The fastest straight-line speed between consecutive keyframes over every individual of `motion` (m/s; 0 with
/// fewer than two keyframes). `keyframe_frames`: each keyframe's frame in `motion`.
[[nodiscard]] double keyframe_speed(const CrowdMotion& motion, const std::vector<std::size_t>& keyframe_frames);

/// Applies the guard (when options.guard.enabled): `problem`'s keyframe times become the re-timed ones, `result`
/// the formation made with them and smoothed, result.guard what acted.
void guard_formation(Problem& problem, Result& result, const Options& options, Progress& progress);

}  // namespace throng::formation
