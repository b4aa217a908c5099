// The two steps' normal matrices in complex form, assembled straight from the features over the free vertices
// (the iterative method's systems; the direct method assembles the real form through throng/linalg).
//
// A feature row is complex-linear in the positions z = x + i y: v − (1 − c) u − c w (step 1's three terms and
// steps 2's temporal and spatiotemporal ones), or an edge v − u, v − w of a spatial feature (step 2's ESC,
// Eq. 10). Q = Σ_rows weight · aᴴ a is Hermitian: Q[p][q] = Σ weight · conj(a_p) a_q, each entry summed over its
// rows in one fixed order (term, then feature index) from both of its ends, so Q is exactly Hermitian and the
// same for any thread count. Rows of a vertex at sample s come from spatial features of s, temporal features of
// s − 1 .. s + 1 and spatiotemporal features of s and s + 1 (the feature's predicted vertex v sets its
// sample): samples are assembled in parallel. Memory: the matrices only (no real-form A, no triplets).
#pragma once

#include <throng/graph/features.h>
#include <throng/linalg/hermitian.h>

#include <Eigen/Core>

#include <vector>

namespace throng::edit {

/// Which objective: step 1 (E1 = ES + α ET + β EST, Eq. 4) or step 2 (E2 = ESC + α′ ET + β′ EST, Eq. 9).
enum class StepKind { deformation, scale_compensation };

/// Vertices split into free ones (unknowns) and pinned ones (handles).
///   free_index  #vertices: position among the free vertices, or −1;   pin_index  #vertices: pin slot, or −1
///   free        the free vertices by agent, then sample;              pinned     the pinned vertices, increasing
/// The free vertices are numbered agent by agent so that each agent's chain (its samples, which the
/// preconditioner's smoother solves together) is one contiguous stretch of every vector.
struct VertexSplit {
  std::vector<int> free_index, pin_index;
  std::vector<int> free, pinned;
  int agents = 0;  ///< vertex v is agent v mod agents at sample v / agents

  /// The split for `handles` (increasing) among `vertices` vertices of `agents` agents per sample.
  static VertexSplit of(std::size_t vertices, int agents, const std::vector<Eigen::Index>& handles);
};

/// Q_FF (#free × #free, Hermitian, both triangles) and Q_FP (#free × #pinned) of one step.
struct ComplexSystem {
  linalg::ComplexSparse FF, FP;
};

/// Assembles one step's normal matrix over the split (see above). alpha, beta: the temporal and spatiotemporal
/// weights of that step.
[[nodiscard]] ComplexSystem assemble_complex(const FeatureSet& features, StepKind step, double alpha, double beta,
                                             const VertexSplit& split);

/// Step 2's right-hand side change from its ESC targets (Eq. 8–10), on the free vertices: Σ weight · conj(a_p)
/// (target − original edge) over the ESC rows, with each triangle's original fitted onto its step-1 copy without
/// scale (the rotation of systems.h's fit_without_scale: a target edge is the original edge turned by it, so the
/// change is (turn − 1) · edge). One pass over the spatial features, samples in parallel. rhs: #free (resized).
///   original, step1  #vertices by 2
///   spatial_ranges  spatial_sample_ranges(features, split): computed once per feature set, since a drag's
///                   rhs is rebuilt on every drag and the ranges are a serial pass over every feature
void esc_rhs(const FeatureSet& features, const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& original,
             const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& step1, const VertexSplit& split,
             const std::vector<std::size_t>& spatial_ranges, Eigen::VectorXcd& rhs);

/// The spatial features by sample: those at sample s are [ranges[s], ranges[s + 1]) (#samples + 1 entries).
std::vector<std::size_t> spatial_sample_ranges(const FeatureSet& features, const VertexSplit& split);

}  // namespace throng::edit
