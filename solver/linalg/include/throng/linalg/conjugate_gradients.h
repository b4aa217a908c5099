// Preconditioned conjugate gradients for complex Hermitian positive definite systems, several right-hand sides
// at once (one independent CG per column, run in lock-step so that one pass over the matrix serves them all).
//
// Stopping rule. A column stops when its last step moved no unknown by more than its tolerance (in the
// unknowns' own units: metres for the editing systems). With a preconditioner that cuts the error by a steady
// factor ρ per iteration (0.2–0.3 for the editor's two-level one), the error left is about ρ/(1 − ρ) times that
// last step, so below the tolerance; docs/commands/edit.md compares it with the direct solve. A column whose
// start already satisfies A x = b (zero residual) takes no step.
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
};

/// CG's vectors, kept by a caller that solves often (each drag): no page is faulted in again per solve.
struct CgWorkspace {
  ComplexBlock R, Z, P, AP;
  /// Set by a caller that already holds B − A X in R (SolutionHistory::start): the solve skips that product.
  /// Cleared by the solve.
  bool residual_given = false;
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
