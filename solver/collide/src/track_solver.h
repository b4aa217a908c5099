// One trajectory's deformation solver (see collide.h "Deformation of one trajectory").
//
// A track is a run of consecutive present frames of one agent: vertices k = 0 .. length−1 at frames
// first + k. Unknowns: the displacement (dx, dy) of every vertex, interleaved. Objective rows: the temporal
// features (v_{k−1}, v_k, v_{k+1}) of the input (weight w(c), Eq. 6) as complex rows on the displacement, and
// anchor rows with weight (mean temporal weight)/spread⁴ on d. Pinned vertices have d = 0 (eliminated). A point
// constraint asks Σ_j c_j d_{v_j} = target (2 rows, free vertices only).
//
// Solve: min |A d|²_W subject to C d = t, exactly, through the Schur complement on a factorisation made once:
//   Q = AᵀWA on the free unknowns is factorised when the track is first pushed (Q = LLᵀ); each solve computes
//   G = Q⁻¹Cᵀ (one forward and one back substitution per constraint row), S = C G (m × m, dense SPD because
//   every vertex carries at most one constraint), λ = S⁻¹ t, d = G λ, then one step of iterative refinement
//   (the residual t − C d through the same S); a residual above 1e-9 of the largest push is a NumericalError.
// No penalty, so no stiffness to balance against the spread: every spread from 1 frame up works (the anchor is
// floored at spread 1,000, see collide.h).
//
// Two implementations of that one method (TrackMethod): `banded` factorises Q in its natural order as a band
// (a vertex couples with its two neighbours on each side: half-bandwidth 5 in interleaved unknowns, no fill) and
// starts each forward substitution at its constraint's first unknown; `linalg` hands the same objective, pins
// and constraint rows to throng/linalg's ConstrainedLeastSquares (CHOLMOD, Schur complement over the added
// constraints). They agree to rounding (tests/collide); the measured choice is in collide.h.
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
///   positions  length by 2: the input trajectory (the features are measured on it)
///   pinned     length flags; at least one vertex must be free
///   options    spread, velocity_weight, min_feature_length, track_method
/// Throws NumericalError when the system is not positive definite.
[[nodiscard]] std::unique_ptr<TrackSolver> make_track_solver(
    const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& positions, const std::vector<char>& pinned,
    const Options& options);

}  // namespace throng::collide
