// Real powers of an orthogonal matrix through its block-diagonal (real Schur) form (§3.2, METHODS.md §2).
#pragma once

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// G (n×n, orthogonal, det +1) = Z U Zᵀ with Z orthogonal and U block diagonal: for plane p < angles().size()
/// a 2×2 rotation [[cos θ_p, −sin θ_p], [sin θ_p, cos θ_p]] on columns 2p, 2p+1 of Z, then 1 on the remaining
/// columns. θ_p ∈ (0, π]: the principal logarithm, the shortest rotation. −1 eigenvalues (which come in pairs
/// when det = +1) are paired into rotations by π. Powers: G^c = Z U(c) Zᵀ with every θ_p scaled by c, exact for
/// every real c (negative too).
///
/// How: the planes of G are the eigenspaces of its symmetric part A = (G + Gᵀ)/2 (eigenvalue cos θ). After one
/// symmetric eigen-decomposition A = V C Vᵀ, W = Vᵀ G V is block diagonal up to rounding, with blocks where
/// eigenvalues of A repeat or nearly repeat (equal angles; the ±1 eigenspaces). Each block (found as a connected
/// set of entries above the rounding level) is resolved exactly as a normal matrix: the Hermitian matrix
/// Sym(B) − iγ Skew(B) shares B's eigenvectors and separates conjugate pairs, so one Hermitian eigen-solve gives
/// the invariant planes of B; what is left is the ±1 eigenspace, split by the sign of Sym(B). Blocks are tiny
/// for generic rotations; the cost is that of one symmetric eigenproblem, about a quarter of a general real
/// Schur decomposition and far faster than LAPACK's dgees at n ≥ 1,000 on this machine.
class RotationPower {
 public:
  /// The identity of size n.
  static RotationPower identity(int n);
  /// Decomposes g; throws NumericalError if g is not orthogonal with det +1 (to rounding).
  explicit RotationPower(const Eigen::Ref<const Eigen::MatrixXd>& g);

  [[nodiscard]] int size() const noexcept { return size_; }
  /// True when G is the identity to rounding: then basis() is empty and powers are the identity.
  [[nodiscard]] bool is_identity() const noexcept { return angles_.empty(); }
  /// Z (n×n); empty for the identity.
  [[nodiscard]] const Eigen::MatrixXd& basis() const noexcept { return basis_; }
  /// θ_p of each plane p.
  [[nodiscard]] const std::vector<double>& angles() const noexcept { return angles_; }

  /// w ← U(c) w, where the rows of w are coordinates in Z and its columns come in consecutive groups of `group`
  /// columns, group i taking exponent exponents[i] (so one call rotates every frame of a batch).
  void rotate(Eigen::Ref<Eigen::MatrixXd> w, const std::vector<double>& exponents, int group) const;

  /// G^c as a dense matrix (tests and small groups).
  [[nodiscard]] Eigen::MatrixXd power(double c) const;

 private:
  RotationPower() = default;
  int size_ = 0;
  Eigen::MatrixXd basis_;
  std::vector<double> angles_;
};

}  // namespace throng::formation
