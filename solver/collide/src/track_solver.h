// One trajectory's deformation solver (see collide.h "Deformation of one trajectory").
//
// A track is a run of consecutive present frames of one agent: vertices k = 0 .. length−1 at frames
// first + k. Unknowns: the displacement (dx, dy) of every vertex, interleaved. Objective rows: the temporal
// features (v_{k−1}, v_k, v_{k+1}) of the input (weight w(c), Eq. 6) as complex rows on the displacement, and
// anchor rows with weight (mean temporal weight)/spread⁴ on d. Pinned vertices have d = 0 (eliminated). A point
// constraint asks Σ_j c_j d_{v_j} = target (2 rows, free vertices only).
//
// Solve. With pins at 0 and a zero right-hand side the result is min |A d|²_W subject to C d = t. The constraint
// rows are added as a stiff penalty: (Q + ρ CᵀC) d = ρ Cᵀ t with Q = AᵀWA on the free unknowns and
// ρ = 1e7 · max diag(Q), so C d − t is ~1e-7 of the push (checked after every solve: a residual above 1e-5 of
// the largest target is a NumericalError). Q is banded (a vertex couples with its two neighbours on each side:
// half-bandwidth 5 in interleaved unknowns) and a constraint couples two neighbouring vertices, inside the band,
// so every iteration is one banded refactorisation in natural order (Eigen's simplicial Cholesky, no fill, no
// BLAS) and one solve: O(length) per trajectory however many points it pushes. Measured on the Figure 8 scene
// (50 agents × 450 frames, ~30 pushed points per trajectory and iteration): throng/linalg's
// ConstrainedLeastSquares (CHOLMOD supernodal, Schur complement over the constraints) spent 2.1 s in dense BLAS
// triangular solves, an exact Schur complement on the banded factor 1.1 s (one back-substitution per constraint
// row); see the report for the penalty's time.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

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
  ///   positions  length by 2: the input trajectory (the features are measured on it)
  ///   pinned     length flags; at least one vertex must be free
  TrackSolver(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& positions, const std::vector<char>& pinned,
              double spread, double min_feature_length);

  /// The displacement (length by 2) meeting `constraints` (on free vertices, each vertex in at most one), pins 0.
  /// Throws NumericalError when the system is not positive definite or the pushes are not met.
  [[nodiscard]] Eigen::Matrix<double, Eigen::Dynamic, 2> solve(const std::vector<PointConstraint>& constraints);

 private:
  using Sparse = Eigen::SparseMatrix<double>;
  Eigen::Index length_;
  std::vector<Eigen::Index> free_of_;     // unknown → free index, −1 when pinned
  std::vector<Eigen::Index> unknown_of_;  // free index → unknown
  Sparse Q_;                              // free part of AᵀWA, with the whole band stored (explicit zeros)
  double stiffness_ = 0.0;                // ρ
  Eigen::SimplicialLLT<Sparse, Eigen::Lower, Eigen::NaturalOrdering<int>> factor_;
};

}  // namespace throng::collide
