// The Editor's two steps (step 1, the deformation; step 2, scale compensation) behind one interface, with two
// methods (linalg::SolverOptions::method):
//   direct     direct_steps.h: both objectives through throng/linalg's ConstrainedLeastSquares on a backend
//              (CHOLMOD: exact to rounding);
//   iterative  iterative_steps.h: conjugate gradients with a two-level space-time preconditioner on the complex
//              normal matrices (to SolverOptions::position_tolerance).
// Both eliminate the handles, meet general constraints through a Schur complement, and keep what a new drag of
// the same handles can reuse.
#pragma once

#include "request.h"

#include <throng/edit/edit.h>

#include <Eigen/Core>

namespace throng::edit {

using Positions = Eigen::Matrix<double, Eigen::Dynamic, 2>;

class EditSteps {
 public:
  virtual ~EditSteps() = default;

  /// The request in solver terms. `previous` is the one applied before (nullptr: none): only what changed
  /// (handle set, handle basis, constraint rows) is invalidated.
  virtual void apply(const ResolvedRequest& resolved, const ResolvedRequest* previous) = 0;

  /// Redoes what apply() made stale (analysis, factorisation or preconditioners, handle bases, Schur
  /// complements) for the request last applied. Throws linalg errors (SingularMatrixError, NumericalError).
  virtual void precompute(const ResolvedRequest& current) = 0;

  /// Whether drags will follow the first solve after the next precompute (an interactive editor, the default) or
  /// not (a one-off edit): a method may prepare for them there (IterativeSteps seeds its drags' start).
  virtual void expect_drags(bool drags_follow) { (void)drags_follow; }

  /// Whether solve() would need precompute() first.
  [[nodiscard]] virtual bool is_ready() const = 0;

  /// Both steps for `current` (the request last applied; its coordinates and constraint values may be new):
  /// step 1's positions in x1, the final ones in x2 (#vertices by 2; x2 = x1 without scale compensation).
  /// Fills the report's solve fields. Throws linalg::ConstraintError for constraints that cannot be met.
  virtual void solve(const ResolvedRequest& current, Positions& x1, Positions& x2, Report& report) = 0;

  /// Adds the last precompute's facts (timings, factor sizes, method) and the running counts to the report.
  virtual void describe(Report& report) const = 0;
};

}  // namespace throng::edit
