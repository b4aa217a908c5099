// The direct method of the Editor (edit_steps.h): both objectives in real form through throng/linalg's
// ConstrainedLeastSquares, both factorised once per handle set (CHOLMOD supernodal, complex LLᴴ; step 2 reuses
// step 1's symbolic analysis). A drag of the same handles costs step 1 a dense product (its pins are
// coordinates in the handles' basis, and its b never changes) and step 2 one pair of triangular sweeps.
#pragma once

#include "edit_steps.h"
#include "systems.h"

#include <throng/graph/features.h>
#include <throng/linalg/least_squares.h>

namespace throng::edit {

class DirectSteps final : public EditSteps {
 public:
  /// Assembles both objectives (step 2 only with scale compensation) over `original` (#vertices by 2).
  DirectSteps(const FeatureSet& features, const Positions& original, const Options& options);

  void apply(const ResolvedRequest& resolved, const ResolvedRequest* previous) override;
  void precompute(const ResolvedRequest& current) override;
  [[nodiscard]] bool is_ready() const override;
  void solve(const ResolvedRequest& current, Positions& x1, Positions& x2, Report& report) override;
  void describe(Report& report) const override;

 private:
  const FeatureSet& features_;
  const Positions& original_;
  Options options_;
  Objective step1_, step2_;  // their A handed to the solvers (empty here); weights and b kept
  linalg::ConstrainedLeastSquares step1_solver_, step2_solver_;
  double precompute_seconds_ = 0;
};

}  // namespace throng::edit
