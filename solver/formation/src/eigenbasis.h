// Laplacian eigenbases and their alignment from one keyframe to the next (§3.2, §4.2).
#pragma once

#include <throng/formation/formation.h>

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// Orthonormal eigenvectors (columns) of a Laplacian and values(j), the eigenvalue of column j. From
/// laplacian_eigenbasis the values ascend and column 0 is exactly 1/√n (the graph is connected, so λ1 = 0 is
/// simple and its eigenvector is constant); from align_basis the columns are in the pairing order of the chain
/// (column j of keyframe k is paired with column j of keyframe k−1) and each keeps its own eigenvalue.
struct Eigenbasis {
  Eigen::MatrixXd vectors;
  Eigen::VectorXd values;
};
[[nodiscard]] Eigenbasis laplacian_eigenbasis(Eigen::MatrixXd laplacian);

/// The target basis aligned to `source` (the previous keyframe's aligned basis), both #items by #items. The
/// source is taken in ITS OWN eigenvalue order (its columns sorted by `source.values`, column 0 first), as if it
/// were the first keyframe: the paper's "fix the source order; for k = 2..n choose greedily ... e^S_k" (§4.2).
/// Visiting the source in the column order a chain inherited from keyframe 0 would make the pairing, and so the
/// path between two keyframes, depend on the keyframes before them. In that order:
///   1. within every repeated target eigenvalue (relative spread ≤ 1e-8 of the largest), the target vectors are
///      rotated onto the source vectors of the same indices (orthogonal Procrustes);
///   2. target vectors are reordered (`reordering`; column 0 stays);
///   3. each vector is flipped if <e^S_j, e^T_j> < 0;
///   4. if det(sourceᵀ M) = −1, the vector with the smallest |<e^S_j, e^T_j>| (j ≥ 2) is flipped.
/// The result's column c is the target vector paired with source column c (column positions are kept), with
/// its eigenvalue in values(c). Flipping or rotating eigenvectors changes the coefficients, never the positions
/// they describe; permuting the source's columns permutes sourceᵀ M on both sides, so its determinant is kept.
[[nodiscard]] Eigenbasis align_basis(const Eigenbasis& source, Eigenbasis target, Reordering reordering);

/// Target index for each source index j (order[0] = 0) from the inner products g = sourceᵀ target: greedily
/// for j = 1, 2, ... the unused target with the largest |g(j, ·)| (lowest index on ties).
[[nodiscard]] std::vector<int> greedy_order(const Eigen::MatrixXd& g);

/// The order maximising min_j |g(j, order[j])| over j ≥ 1 (bottleneck assignment: binary search on the value
/// with Hopcroft–Karp matchings), and among those the largest Σ_j |g(j, order[j])| (minimum-cost assignment).
[[nodiscard]] std::vector<int> max_min_order(const Eigen::MatrixXd& g);

}  // namespace throng::formation
