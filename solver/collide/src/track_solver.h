// One trajectory's deformation solver (see collide.h "Deformation of one trajectory").
//
// A track is a run of consecutive present frames of one agent: vertices k = 0 .. length−1 at frames
// first + k. Unknowns: the displacement (dx, dy) of every vertex, interleaved. Objective rows: the temporal
// features (v_{k−1}, v_k, v_{k+1}) of the input (weight w(c), Eq. 6) as complex rows on the displacement,
// velocity rows d_{k+1} − d_k (weight velocity_weight · mean temporal weight) and anchor rows on d (that weight /
// spread²; with velocity_weight 0, mean temporal weight / spread⁴). Pinned vertices have d = 0 (eliminated). A point
// constraint asks Σ_j c_j d_{v_j} = target (2 rows, free vertices only).
//
// With smoothing_time T > 0 (the default) the velocity and anchor rows are replaced by the smoothing in time of
// collide.h: acceleration rows d_{k−1} − 2 d_k + d_{k+1} (weight λ w̄, λ = smoothing_weight), velocity rows
// (2 λ w̄ / n²) and anchor rows (λ w̄ / n⁴), n = T / interval_s frames (at most 1,000).
//
// Solve: min |A d|²_W subject to C d = t, exactly, with Q = AᵀWA on the free unknowns assembled (and factorised)
// once, when the track is first pushed. Every vertex carries at most one constraint (the repair takes disjoint
// contacts); a residual above 1e-7 of the largest push (rounding, see check_met) is a NumericalError. No penalty, so no stiffness to
// balance against the spread: every spread from 1 frame up works (the anchor is floored at spread 1,000, see
// collide.h).
//
// Three implementations of that one method (TrackMethod); they agree to rounding (tests/collide
// test_track_solver), the measured choice is in collide.h:
//  * `eliminate`: each row c_e x_e + c_o x_o = t is solved for the unknown with the larger |c|, the rest is a
//    band system (half-bandwidth ≤ 9) that differs from Q only in a window around the pushed unknowns; the
//    unknowns before and after the window are eliminated through Q = L Lᵀ and the reversed factor of Q (both
//    once), and only the window is factorised per solve (details at the class);
//  * `schur`: Q = L Lᵀ as a band once (a vertex couples with its two neighbours on each side: half-bandwidth 5
//    in interleaved unknowns, no fill); per solve G = Q⁻¹Cᵀ (forward substitutions starting at each row's first
//    unknown), S = C G (m × m, dense SPD), λ = S⁻¹ t, d = G λ, one step of iterative refinement through S;
//  * `linalg`: the same objective, pins and constraint rows through throng/linalg's ConstrainedLeastSquares
//    (CHOLMOD, Schur complement over the added constraints).
#pragma once

#include <throng/collide/collide.h>

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace throng::collide {

/// A prescribed displacement of a point c0 d_{v0} + c1 d_{v1} (c1 = 0 when only one vertex carries it).
struct PointConstraint {
  int v0 = 0, v1 = 0;
  double c0 = 1.0, c1 = 0.0;
  Eigen::Vector2d target{0, 0};
};

class TrackSolver {
 public:
  virtual ~TrackSolver() = default;
  /// The displacement (length by 2) meeting `constraints` (on free vertices, each vertex in at most one), pins 0.
  /// Throws NumericalError when the pushes cannot be met.
  [[nodiscard]] virtual Eigen::Matrix<double, Eigen::Dynamic, 2> solve(const std::vector<PointConstraint>& constraints) = 0;
};

/// Assembles and factorises one track's system (once).
///   positions   length by 2: the input trajectory (the features are measured on it)
///   pinned      length flags; at least one vertex must be free
///   options     smoothing_time, smoothing_weight (or spread, velocity_weight), min_feature_length, track_method
///   interval_s  the track's mean frame interval (seconds): h of the smoothing rows
/// Throws NumericalError when the system is not positive definite.
[[nodiscard]] std::unique_ptr<TrackSolver> make_track_solver(
    const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& positions, const std::vector<char>& pinned,
    const Options& options, double interval_s);

}  // namespace throng::collide
