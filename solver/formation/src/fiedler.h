// The Fiedler vector of a graph (the Laplacian eigenvector of the second smallest eigenvalue), which the
// automatic hierarchy bisects groups by (§4.4, hierarchy.h).
#pragma once

#include "adjacency.h"

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// Fiedler vector of the subgraph of `graph` induced on `subset` (#subset, entry i for item subset[i]): a unit
/// vector orthogonal to the constant one minimising vᵀLv, sign fixed so its largest-magnitude entry is positive
/// (the first such entry on ties). When the induced subgraph is not connected, λ2 = 0 and its eigenvectors are
/// constant on each component: the vector returned is the component numbers (0, 1, ... in the order of their
/// first item) centred and normalised, so sorting by it keeps components together. Deterministic: no
/// thread-count dependence, the same bits for the same input.
///
/// Up to `dense_fiedler_limit` items: the full symmetric eigen-decomposition (LAPACK, O(m³)). Beyond, the
/// smallest eigenpair of L away from the constant vector by Lanczos (Spectra), never a dense m × m matrix:
///   - shift-invert, solving with a sparse LDLᵀ factor of L + sI (Eigen, AMD ordering; s a tiny shift that
///     makes it definite), when the factor is cheap: graphs with small separators, as a crowd whose keyframes
///     keep neighbours together gives (a few products with the factor);
///   - otherwise plain Lanczos on L: graphs without small separators have a large λ2 and converge quickly.
/// A 10,000-individual crowd's graph is bisected in a fraction of a second rather than the minutes (and
/// 0.8 GB) of a dense 10,000² eigen-decomposition. Throws NumericalError if Lanczos does not converge.
/// `solver` other than automatic forces one way (tests); shift_invert needs the factor to succeed.
enum class FiedlerSolver { automatic, dense, shift_invert, lanczos };
[[nodiscard]] Eigen::VectorXd fiedler_vector(const Adjacency& graph, const std::vector<int>& subset,
                                             FiedlerSolver solver = FiedlerSolver::automatic);

/// Subsets of at most this many items use the dense eigen-decomposition.
inline constexpr int dense_fiedler_limit = 400;

}  // namespace throng::formation
