// The section-1 solve (paper §4, Eq. 4–10) over a feature set the caller built: E1 = ES + α ET + β EST with
// pinned vertices, then scale compensation E2 = ESC + α′ ET + β′ EST. For methods that make their own features
// and targets — stitching blends them from two clips (paper §5) — and need the editing energy without an
// Editor's clip and request. The systems are the Editor's (same rows, same weights, same solver setup).
#pragma once

#include <throng/graph/features.h>
#include <throng/linalg/solver_options.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace throng::edit {

/// The terms' weights (Eq. 4 and 9), as in edit::Options.
struct FeatureWeights {
  double alpha = 1.0;        ///< α: temporal term in step 1, ≥ 0
  double beta = 1.0;         ///< β: spatiotemporal term in step 1, ≥ 0
  double alpha_prime = 1.0;  ///< α′: temporal term in step 2, ≥ 0
  double beta_prime = 1.0;   ///< β′: spatiotemporal term in step 2, ≥ 0
  bool scale_compensation = true;  ///< run step 2
};

/// Results and facts of one solve.
///   positions, step1  #vertices by 2 (metres)
struct FeatureDeformation {
  Eigen::Matrix<double, Eigen::Dynamic, 2> positions;  ///< final (step 2's, or step 1's without compensation)
  Eigen::Matrix<double, Eigen::Dynamic, 2> step1;
  std::string factorization;        ///< backend method of step 1
  double assemble_seconds = 0;      ///< both objectives
  double precompute_seconds = 0;    ///< analyse and factorise both steps
  double solve_seconds = 0;         ///< step 1, fitting, step 2
};

/// Minimises E1 over the vertices the features name with `pinned` vertices fixed at `targets`, then (when
/// weights.scale_compensation) fits every spatial feature's triangle of `original` onto its step-1 copy without
/// scale (Eq. 8) and minimises E2 (Eq. 9–10).
///   original  #vertices by 2: the positions the features were measured on (the triangles step 2 restores)
///   pinned    #pinned distinct vertex indices;   targets  #pinned by 2 (metres)
/// Throws ConfigError for a negative or non-finite weight, NumericalError when the pins leave a part of the graph
/// free to move (the system is singular).
[[nodiscard]] FeatureDeformation deform_with_features(const FeatureSet& features,
                                                      const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& original,
                                                      const std::vector<Eigen::Index>& pinned,
                                                      const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& targets,
                                                      const FeatureWeights& weights, const linalg::SolverOptions& solver = {});

}  // namespace throng::edit
