// Local features of the motion graph (paper Eq. 1–7) and their weights.
//
// A feature c = (u, v, w) predicts vertex v from u and w (Eq. 1–2): in complex notation, with R the rotation by
// +90°, v = u + cx (w − u) + cy R (w − u) = u + c (w − u) where c = cx + i cy. The deformation asks each
// deformed v' to stay at f_c(u', w') = u' + c (w' − u') (Eq. 3), weighted by w(c).
//
//  * spatial (Eq. 5): each formation triangle (a, b, c) at a sample gives (a, b, c), (b, c, a), (c, a, b);
//  * temporal (Eq. 6): (v(i−1, j), v(i, j), v(i+1, j)) — agent j's trajectory through sample i;
//  * spatiotemporal (Eq. 7): (v(i−1, j), v(i, j), v(i, k)) for every formation neighbour k of j at sample i ≥ 1.
//    The paper writes the triple (v_{t−1}, w_t, v_t) and says v_t is joined to the other two by a motion and a
//    formation edge: the predicted vertex is v(i, j), framed by its own previous position and its neighbour
//    now, so the step v(i−1, j) → v(i, j) keeps its angle to the direction of the neighbour (paper Figure 5).
//
// Weights. The paper weights spatial features by 1/(|vu|² + |vw|²) in the original graph "for discounting
// distant formations" and writes Eq. 6–7 without a weight. Decision: every feature gets the same weight rule,
// 1/max(|vu|² + |vw|², ℓ²) with ℓ = FeatureOptions::min_length. Every term is then a relative (unit-free)
// distortion, so α and β mean the same thing whatever the units, speeds and sampling; ℓ keeps an agent
// standing still (|vu| = |vw| = 0) from getting an infinite weight.
//
// Degenerate frames. When |w − u| is tiny against |v − u| + |v − w| (an agent standing still, or turning back
// between samples), c is undefined or huge. Such a feature instead keeps v at the midpoint of u and w plus its
// original offset: f(u, w) = u + ½ (w − u) + r with r = v − (u + w)/2 (exact on the original graph, translation
// invariant, and harmless to rotation because r is small where this happens).
#pragma once

#include <throng/graph/motion_graph.h>

#include <complex>
#include <vector>

namespace throng {

/// One feature: f(u', w') = u' + c (w' − u') + offset predicts v'. Indices are graph vertices.
struct Feature {
  int u = 0;
  int v = 0;
  int w = 0;
  std::complex<double> c{0, 0};       ///< local coordinates cx + i cy (Eq. 1)
  std::complex<double> offset{0, 0};  ///< 0 except for degenerate features (see above), metres
  double weight = 1.0;                ///< w(c), 1/m²
};

struct FeatureOptions {
  /// ℓ in the weight rule, metres: feature arm lengths below this count as this (see above).
  double min_length = 0.05;
  /// A feature is degenerate when |w − u| ≤ degenerate_ratio · (|v − u| + |v − w|).
  double degenerate_ratio = 1e-3;
};

/// The three feature sets of a graph, measured on its original positions, in a fixed order (by sample, then by
/// triangle, agent or edge), so the system built from them does not depend on the thread count. Spatial
/// features come in threes: spatial[3t], [3t + 1], [3t + 2] are the corners (a, b, c), (b, c, a), (c, a, b) of
/// one triangle.
struct FeatureSet {
  std::vector<Feature> spatial;
  std::vector<Feature> temporal;
  std::vector<Feature> spatiotemporal;
};

/// Computes the features (in parallel over samples, deterministic).
[[nodiscard]] FeatureSet compute_features(const MotionGraph& graph, const FeatureOptions& options = {});

/// The feature for prediction of v from u and w at the given positions (exposed for tests and stitching).
[[nodiscard]] Feature make_feature(int u, int v, int w, const Eigen::Vector2d& pu, const Eigen::Vector2d& pv,
                                   const Eigen::Vector2d& pw, const FeatureOptions& options);

}  // namespace throng
