// Laplacian eigenbases and their alignment from one keyframe to the next (§3.2, §4.2).
#pragma once

#include <throng/formation/formation.h>

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// Eigenvalues ascending and orthonormal eigenvectors (columns) of a Laplacian; column 0 is exactly 1/√n
/// (the graph is connected, so λ1 = 0 is simple and its eigenvector is constant).
struct Eigenbasis {
  Eigen::MatrixXd vectors;
  Eigen::VectorXd values;
};
[[nodiscard]] Eigenbasis laplacian_eigenbasis(Eigen::MatrixXd laplacian);

/// The target basis aligned to `source` (the previous keyframe's aligned basis), both #items by #items:
///   1. within every repeated target eigenvalue (relative spread ≤ 1e-8 of the largest), the target vectors are
///      rotated onto the source vectors of the same indices (orthogonal Procrustes);
///   2. target vectors are reordered (`reordering`; column 0 stays);
///   3. each vector is flipped if <e^S_j, e^T_j> < 0;
///   4. if det(sourceᵀ M) = −1, the vector with the smallest |<e^S_j, e^T_j>| (j ≥ 2) is flipped.
/// Flipping or rotating eigenvectors changes the coefficients, never the positions they describe.
[[nodiscard]] Eigen::MatrixXd align_basis(const Eigen::MatrixXd& source, Eigenbasis target, Reordering reordering);

/// Target index for each source index j (order[0] = 0) from the inner products g = sourceᵀ target: greedily
/// for j = 1, 2, ... the unused target with the largest |g(j, ·)| (lowest index on ties).
[[nodiscard]] std::vector<int> greedy_order(const Eigen::MatrixXd& g);

/// The order maximising min_j |g(j, order[j])| over j ≥ 1 (bottleneck assignment: binary search on the value
/// with Hopcroft–Karp matchings), and among those the largest Σ_j |g(j, order[j])| (minimum-cost assignment).
[[nodiscard]] std::vector<int> max_min_order(const Eigen::MatrixXd& g);

}  // namespace throng::formation
