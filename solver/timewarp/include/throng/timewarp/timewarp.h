// Time warping (Kwon et al. 2008, §6.2, Eq. 12; docs/METHODS.md §1.2): a deformed crowd whose paths
// got longer or shorter walks faster or slower than the original; one time warp shared by every agent brings the
// speeds back as close to the original's as it can, then every agent is resampled at the output frame rate
// through non-uniform cubic interpolating splines (throng/timewarp/spline.h, not-a-knot ends).
//
// Method. Unknowns s_i = 1/Δt'_i, one per frame interval i of the deformed crowd. Eq. 12 asks
//     Σ_i Σ_j ( |v'(i+1,j) − v'(i,j)| s_i − |v(i+1,j) − v(i,j)| / Δt_i )²
// to be least (v: the reference, i.e. the crowd before the deformation, at the same frames; v': the deformed
// crowd; Δt_i its i-th frame interval — the paper's Δt is constant, here each interval's own length is used, the
// same thing for uniform frames). The sum is separable: with A_i = Σ_j a_ij² and B_i = Σ_j a_ij b_ij (a: deformed
// step length, b: reference speed), s_i = B_i / A_i, a closed form per interval.
//
// Decisions where the paper is open:
//  * Smoothness (off by default): written on the speed-up ratio r_i = s_i Δt_i = Δt_i / Δt'_i as
//      Σ_i P_i (r_i − r*_i)² + Σ_i P̄_i (σ / τ_i)² (r_{i+1} − r_i)²,   P_i = A_i / Δt_i²,  r*_i = B_i Δt_i / A_i,
//    with P̄_i = (P_i + P_{i+1})/2 and τ_i the time between the two intervals' midpoints. σ = smoothing_time (s)
//    is the time scale over which the warp may change: the balance of the two sums does not depend on the
//    frame rate. The minimum solves a tridiagonal system.
//  * Clamp: the interval ratio Δt'_i / Δt_i is kept in [min_interval_ratio, max_interval_ratio] (positive), as
//    box constraints: exact per interval without smoothing (the clamped closed form); with smoothing, an active-
//    set loop over the tridiagonal system (fixed at a bound while the gradient pushes outward). The report counts
//    the intervals held at each bound, so callers can say when the clamp acts.
//  * Still intervals: where no agent moves in the deformed crowd (A_i = 0) nothing says how long the interval
//    should be; it keeps its length (r = 1), weakly (weight 10⁻³ × the mean P) so smoothing can still act on it.
//    If nobody moves anywhere the warp is the identity.
//  * Terms use only the (interval, agent) pairs where the agent is present at both frames in both crowds, so
//    agents entering and leaving are fine. Steps are measured in 3-D (z is 0 for 2-D crowds).
//  * Output: frames at start, start + 1/rate, ... up to the one nearest the warped end (within half an output
//    interval of it, before or after); the first frame keeps its time. An agent's first and last samples land on
//    the output frames nearest their warped times (resample_crowd's end slack of half an output interval, the end
//    position held): a small warp (tens of ms) moves no sample off the output. The report's duration is that of
//    the frames written. Velocities are the splines' derivatives; facing (slerp) and actions (the sample at or
//    before) are carried when the input has them.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/timewarp/spline.h>

#include <cstdint>
#include <vector>

namespace throng::timewarp {

struct Options {
  /// σ, seconds ≥ 0: the time scale over which the warp's speed-up may change (see above); 0 = the closed form
  /// per interval (the paper).
  double smoothing_time = 0.0;
  /// Bounds of Δt'_i / Δt_i, 0 < min ≤ 1 ≤ max: how much an interval may shrink or stretch.
  double min_interval_ratio = 0.25;
  double max_interval_ratio = 4.0;
  /// Frames per second of the output; 0 = the input's rate (1 / its median frame interval).
  double output_rate_hz = 0.0;
  /// End condition of the resampling splines.
  SplineEnd spline_end = SplineEnd::not_a_knot;
  /// Seconds: a reference frame matches a frame of the deformed crowd when their times differ by at most this.
  double time_tolerance_s = 1e-6;
};

/// Checks the option values; ConfigError naming the option, the value and what was expected.
void validate(const Options& options);

/// The warp, old time → new time, at the deformed crowd's frames.
///   source_times       #frames: the deformed crowd's times (old)
///   warped_times       #frames: new times; warped_times[0] = source_times[0]
///   inverse_intervals  #frames − 1: s_i = 1 / Δt'_i (1/s)
///   bound              #frames − 1: 0 free, −1 held at min_interval_ratio, +1 held at max_interval_ratio
struct Warp {
  std::vector<double> source_times;
  std::vector<double> warped_times;
  std::vector<double> inverse_intervals;
  std::vector<std::int8_t> bound;

  /// The new time of `old_time`, linear between frames (and beyond the ends, with the end intervals' ratio).
  [[nodiscard]] double map(double old_time) const;
};

/// What the warp did. Speed deviations are root mean squares of Eq. 12's residual over its terms (m/s): before =
/// with the original frame intervals, after = with the warped ones.
struct Report {
  std::size_t frames_in = 0, frames_out = 0, agents = 0;
  std::size_t terms = 0;              ///< (interval, agent) pairs in Eq. 12
  std::size_t clamped_short = 0;      ///< intervals held at min_interval_ratio
  std::size_t clamped_long = 0;       ///< intervals held at max_interval_ratio
  std::size_t still_intervals = 0;    ///< intervals where no agent moves
  int active_set_iterations = 0;
  double speed_deviation_before = 0, speed_deviation_after = 0;  ///< m/s
  double reference_speed_rms = 0;     ///< m/s, for scale
  double duration_in_s = 0;           ///< last − first time of the input's frames
  double warped_duration_s = 0;       ///< the warp's span: last − first warped frame time
  double duration_out_s = 0;          ///< last − first time of the frames written (time_warp; 0 from solve_warp)
  double output_rate_hz = 0;
};

struct Result {
  CrowdMotion crowd;  ///< the warped crowd at the output rate, with velocities
  Warp warp;
  Report report;
};

/// The reference at the deformed crowd's frames and agents: agents matched by id, frames by time (within
/// `time_tolerance_s`). Throws InputError naming the first agent id of `deformed` missing from `reference` or the
/// first frame time with no reference frame.
[[nodiscard]] CrowdMotion match_reference(const CrowdMotion& deformed, const CrowdMotion& reference, double time_tolerance_s);

/// Eq. 12 (with the options' smoothing and clamp) for `deformed` against `reference` of the same shape (as
/// match_reference returns it). Fills the report's warp fields when `report` is given.
[[nodiscard]] Warp solve_warp(const CrowdMotion& deformed, const CrowdMotion& reference, const Options& options,
                              Report* report = nullptr);

/// The whole method: match the reference, solve the warp, resample at the output rate.
[[nodiscard]] Result time_warp(const CrowdMotion& deformed, const CrowdMotion& reference, const Options& options);

}  // namespace throng::timewarp
