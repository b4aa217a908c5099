// Small deterministic least-squares problems for the solver layer's tests.
#pragma once

#include <throng/core/random.h>
#include <throng/linalg/solver_options.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <vector>

namespace throng::test {

/// A random sparse A (#rows = 3·n) with full column rank: every row has 3 random entries, and each unknown also
/// has a row of its own, so AᵀA is well conditioned (cond ≈ 10², measured) and errors stay near ε·cond.
inline linalg::SparseMatrix random_objective(Eigen::Index n, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index r = 0; r < 2 * n; ++r) {
    for (int k = 0; k < 3; ++k) t.emplace_back(r, static_cast<Eigen::Index>(rng.below(static_cast<std::uint64_t>(n))), rng.uniform(-1, 1));
  }
  for (Eigen::Index i = 0; i < n; ++i) t.emplace_back(2 * n + i, i, 1.0 + rng.uniform());
  linalg::SparseMatrix A(3 * n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

/// Uniform random weights in [0.5, 2).
inline Eigen::VectorXd random_weights(Eigen::Index rows, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::VectorXd w(rows);
  for (Eigen::Index i = 0; i < rows; ++i) w[i] = rng.uniform(0.5, 2.0);
  return w;
}

inline Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = rng.uniform(-1, 1);
  return m;
}

/// The same problem solved densely through its KKT system (the reference): unknowns x and multipliers for
/// pins and constraints, [Q Eᵀ; E 0] [x; μ] = [AᵀWb; e] with E = [pin selection; C].
inline Eigen::VectorXd dense_reference(const linalg::SparseMatrix& A, const Eigen::VectorXd& w, const Eigen::VectorXd& b,
                                       const std::vector<Eigen::Index>& pinned, const Eigen::VectorXd& pin_values,
                                       const Eigen::MatrixXd& C, const Eigen::VectorXd& d) {
  const Eigen::Index n = A.cols();
  const Eigen::Index p = static_cast<Eigen::Index>(pinned.size());
  const Eigen::Index m = C.rows();
  const Eigen::MatrixXd Ad(A);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + p + m, n + p + m);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + p + m);
  K.topLeftCorner(n, n) = Ad.transpose() * w.asDiagonal() * Ad;
  rhs.head(n) = Ad.transpose() * w.asDiagonal() * b;
  for (Eigen::Index k = 0; k < p; ++k) {
    K(n + k, pinned[static_cast<std::size_t>(k)]) = K(pinned[static_cast<std::size_t>(k)], n + k) = 1.0;
    rhs[n + k] = pin_values[k];
  }
  if (m > 0) {
    K.block(n + p, 0, m, n) = C;
    K.block(0, n + p, n, m) = C.transpose();
    rhs.tail(m) = d;
  }
  return K.fullPivLu().solve(rhs).head(n);
}

}  // namespace throng::test
