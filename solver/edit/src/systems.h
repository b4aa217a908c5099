// The two least-squares systems of the deformation, assembled from the graph's features.
//
// Unknowns: x = (x_0, y_0, x_1, y_1, ...) for graph vertex 0, 1, ... (interleaved). A feature (u, v, w, c, r)
// contributes the complex residual v − u − c (w − u) − r = v − (1 − c) u − c w − r, i.e. two real rows (x and y)
// with the feature's weight times the term's weight (Eq. 5–7 and 9).
//
// Step 1 rows:  [spatial | α temporal | β spatiotemporal]                 b = the features' offsets r
// Step 2 rows:  [ESC: 2 edges × 2 coordinates per spatial feature | α′ temporal | β′ spatiotemporal]
//               b = the fitted edges (filled per drag by set_step2_targets) then the offsets r
#pragma once

#include <throng/graph/features.h>
#include <throng/linalg/solver_options.h>

#include <Eigen/Core>

namespace throng::edit {

/// A least-squares objective |W^(1/2) (A x − b)|².
struct Objective {
  linalg::SparseMatrix A;   ///< #rows by 2·#vertices
  Eigen::VectorXd weights;  ///< #rows
  Eigen::VectorXd b;        ///< #rows (for step 2, the ESC part is refreshed per drag)
};

/// E1 = ES + α ET + β EST (Eq. 4).
[[nodiscard]] Objective step1_objective(const FeatureSet& features, Eigen::Index vertices, double alpha, double beta);

/// E2 = ESC + α′ ET + β′ EST (Eq. 9), with the ESC targets zero until set_step2_targets().
[[nodiscard]] Objective step2_objective(const FeatureSet& features, Eigen::Index vertices, double alpha_prime,
                                        double beta_prime);

/// Fills the ESC targets of a step-2 objective (Eq. 10): for each spatial feature (u, v, w), the edge vectors
/// v_F − u_F and v_F − w_F of the original triangle fitted onto its step-1 copy without scale (Eq. 8).
///   original, step1  #vertices by 2
void set_step2_targets(const FeatureSet& features, const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& original,
                       const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& step1, Eigen::VectorXd& b);

/// The rigid (rotation + translation) least-squares fit of triangle `from` onto triangle `to` (3 by 2 each),
/// returned as the fitted copy of `from` (3 by 2). Equals Igarashi et al.'s similarity fit scaled back to the
/// original size (see edit.h).
[[nodiscard]] Eigen::Matrix<double, 3, 2> fit_without_scale(const Eigen::Matrix<double, 3, 2>& from,
                                                            const Eigen::Matrix<double, 3, 2>& to);

/// The similarity modes of the unconstrained step-1 energy (translations, rotation, scaling of all vertices),
/// interleaved x, y: 2·#vertices by 4, a near-null-space hint for multigrid backends.
///   p  #vertices by 2
[[nodiscard]] Eigen::MatrixXd similarity_modes(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& p);

/// An unknown vector x (2·#vertices, interleaved as above) as positions, #vertices by 2.
[[nodiscard]] Eigen::Matrix<double, Eigen::Dynamic, 2> as_positions(const Eigen::MatrixXd& x);

/// Same shape, pattern and values (both compressed, as setFromTriplets leaves them): whether a request's
/// handle basis or constraint rows changed, so a solver's cached work can be kept.
[[nodiscard]] bool same_matrix(const linalg::SparseMatrix& a, const linalg::SparseMatrix& b);

}  // namespace throng::edit
