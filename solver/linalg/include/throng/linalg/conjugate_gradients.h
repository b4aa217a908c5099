// Preconditioned conjugate gradients for complex Hermitian positive definite systems, several right-hand sides
// at once (one independent CG per column, run in lock-step so that one pass over the matrix serves them all).
//
// Stopping rule. With a preconditioner that cuts the error by a steady factor ρ per iteration, the error left
// after a step that moved some unknown by s (largest move, in the unknowns' own units: metres for the editing
// systems) is about s ρ/(1 − ρ). A column stops when that estimate is within its tolerance. The largest move does
// not fall steadily (it can drop 4× in one step and rise the next), so ρ is the largest ratio of consecutive
// steps over the last three; for the first step, which has no ratio, the contraction the previous solve with the
// same workspace measured (CgWorkspace::contraction; a warm-started drag's first step is no proof of
// convergence); always at least ½ (the estimate is never below the step itself) and at most 0.95.
// docs/commands/edit.md compares the result with the direct solve. A column whose start already satisfies
// A x = b takes no step.
//
// Every reduction has a fixed order (hermitian.h): the same input gives the same bits for any thread count.
#pragma once

#include <throng/linalg/hermitian.h>
#include <throng/linalg/two_level.h>

#include <vector>

namespace throng::linalg {

/// What a solve did.
struct CgReport {
  int iterations = 0;               ///< the largest iteration count over the columns
  std::vector<int> column_iterations;
  std::vector<double> last_step;    ///< per column, the largest change of an unknown in its last step (0: none)
  std::vector<double> error_estimate;  ///< per column, the estimated error left (see above; 0: no step)
};

/// CG's vectors, kept by a caller that solves often (each drag): no page is faulted in again per solve.
struct CgWorkspace {
  ComplexBlock R, Z, P, AP;
  /// Set by a caller that already holds B − A X in R (SolutionHistory::start): the solve skips that product.
  /// Cleared by the solve.
  bool residual_given = false;
  /// The contraction ρ the last solve with this workspace measured (0: none yet), the stopping rule's ρ for the
  /// next solve's first step.
  double contraction = 0;
};

/// Solves A X = B from the start X (#unknowns by #columns). tolerance: one per column (> 0), or one for all.
/// Throws NumericalError naming the column and its last step when a column has not stopped within
/// max_iterations, and SingularMatrixError when A proves not positive definite.
CgReport conjugate_gradients(const ComplexSparse& A, Preconditioner& M, const ComplexBlock& B, ComplexBlock& X,
                             const std::vector<double>& tolerance, int max_iterations);
/// The same with the caller's workspace.
CgReport conjugate_gradients(const ComplexSparse& A, Preconditioner& M, const ComplexBlock& B, ComplexBlock& X,
                             const std::vector<double>& tolerance, int max_iterations, CgWorkspace& workspace);

}  // namespace throng::linalg
