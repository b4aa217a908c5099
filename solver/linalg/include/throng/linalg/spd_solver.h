// Sparse symmetric positive definite solvers: one small interface, backends chosen at run time by name.
//
// The constrained least-squares solver (least_squares.h) reduces every problem to solves with one SPD matrix;
// this interface is what it needs from a backend. Backends:
//   "eigen"  (default, always built) CHOLMOD supernodal Cholesky through Eigen's CholmodSupport, METIS or AMD
//            ordering chosen by CHOLMOD, with Eigen's SimplicialLDLT as the fallback when CHOLMOD reports failure.
//   "petsc"  (built when THRONG_WITH_PETSC) PETSc KSP, conjugate gradients with algebraic multigrid by default,
//            distributed over the MPI ranks of PETSC_COMM_WORLD. Every rank calls every method in the same order
//            and receives the whole solution. Each rank owns the rows of its METIS parts of the matrix's node
//            graph (petsc_layout.h) and reads only those: after analyze(), owned_columns() names them, and the
//            caller may then hand factorize() a matrix holding only those columns and solve() right-hand sides
//            right only in those rows (least_squares.h assembles just that on each rank).
// No header of this layer includes PETSc or MPI.
#pragma once

#include <throng/core/errors.h>
#include <throng/linalg/solver_options.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <string>
#include <vector>

namespace throng::linalg {

/// The matrix is singular or not positive definite. index() is the row (of the matrix given to factorize, or of
/// the unknowns when rethrown by least_squares.h) where the factorisation broke down, −1 when not known.
class SingularMatrixError : public NumericalError {
 public:
  SingularMatrixError(const std::string& message, Eigen::Index index) : NumericalError(message), index_(index) {}
  [[nodiscard]] Eigen::Index index() const noexcept { return index_; }

 private:
  Eigen::Index index_;
};

/// What the last factorisation did, for logs and reports.
struct FactorizationInfo {
  std::string method;           ///< for example "CHOLMOD supernodal LLᵀ (METIS)", "PETSc cg + gamg"
  std::string fallback_reason;  ///< non-empty when the fallback factorisation was used, saying why
  double factor_nonzeros = 0;   ///< entries of the Cholesky factor (direct backends), 0 otherwise
  double reciprocal_condition = 0;  ///< (min/max diagonal of L)², CHOLMOD's rough estimate of 1/cond (direct backends)
};

/// What the last solve did.
struct SolveInfo {
  int iterations = 0;            ///< largest iteration count over the right-hand sides (iterative backends)
  double relative_residual = 0;  ///< largest ‖Q x − b‖/‖b‖ over the right-hand sides
};

/// A solver for Q X = B with Q sparse, symmetric positive definite.
/// Lifecycle: analyze(pattern) once per sparsity pattern, factorize(values) when values change, solve() per
/// right-hand side. Failures a user can cause (a singular or indefinite Q, no convergence) are NumericalError.
class SpdSolver {
 public:
  virtual ~SpdSolver() = default;
  SpdSolver() = default;
  SpdSolver(const SpdSolver&) = delete;
  SpdSolver& operator=(const SpdSolver&) = delete;

  /// The backend's name ("eigen", "petsc").
  [[nodiscard]] virtual std::string name() const = 0;

  /// True when solve() is a back-substitution with a factor, so that solving for many right-hand sides ahead of
  /// need is cheap (least_squares.h's pin basis: one block of back-substitutions in precompute, none per drag).
  /// False when every column is a Krylov solve of its own: callers then solve with the right-hand side they
  /// actually have, started from a nearby solution (solve_from), instead of precomputing columns.
  [[nodiscard]] virtual bool is_direct() const { return true; }

  /// Symbolic phase for the pattern of `matrix` (#n by #n, both triangles stored, symmetric).
  virtual void analyze(const SparseMatrix& matrix) = 0;

  /// Instead of analyze(matrix): reuse `other`'s symbolic analysis (ordering, supernodes) when `matrix` has the
  /// pattern `other` analysed with the same hints (two systems over one graph, such as the editor's two steps).
  /// Returns false, having done nothing, when this backend cannot (then call analyze()).
  virtual bool adopt_analysis(const SpdSolver& other, const SparseMatrix& matrix) {
    (void)other;
    (void)matrix;
    return false;
  }

  /// The columns (= rows, the matrix being symmetric) of the analysed matrix that this process reads in
  /// factorize(), increasing, and so the rows of right-hand sides and starting values it reads in solve() and
  /// solve_from(); the other columns may be left empty and the other rows hold anything. Empty when it reads
  /// everything (every non-distributed backend, and a distributed one on one rank). Valid until the next analyze().
  [[nodiscard]] virtual std::vector<Eigen::Index> owned_columns() const { return {}; }

  /// Numeric phase: factorises (direct) or builds the preconditioner (iterative) for `matrix`, which has the
  /// pattern given to analyze(). Throws SingularMatrixError when `matrix` is singular or not positive definite
  /// (iterative backends may only find out in solve()), NumericalError when memory does not suffice.
  virtual void factorize(const SparseMatrix& matrix) = 0;

  /// Solves Q X = B column by column. rhs, solution: #n by #right-hand sides. Throws NumericalError when an
  /// iterative backend does not converge.
  virtual void solve(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> solution) = 0;

  /// As solve(), starting iterative backends from the values in `solution` (a previous, nearby solution:
  /// consecutive drags). Direct backends ignore the start.
  virtual void solve_from(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> solution) {
    solve(rhs, solution);
  }

  /// A hint for multigrid backends, given before factorize(): vectors spanning (nearly) the null space of the
  /// operator without its pins, #n by #modes (for example the translations, rotation and scaling of a
  /// formation), and the number of unknowns per node (2 for interleaved x, y; 1 when unknown). Direct backends
  /// ignore it.
  virtual void set_near_null_space(const Eigen::Ref<const Eigen::MatrixXd>& modes, int block_size) {
    (void)modes;
    (void)block_size;
  }

  /// A hint given before analyze(): Q is a complex Hermitian matrix written in real form over interleaved
  /// pairs, Q[2a..2a+1, 2b..2b+1] = [[Re z, −Im z], [Im z, Re z]] (objectives built from rotations and
  /// scalings of 2-D points, such as the editing features). Backends may then work in complex arithmetic.
  virtual void set_complex_pairs(bool complex_pairs) { (void)complex_pairs; }

  [[nodiscard]] virtual const FactorizationInfo& factorization_info() const = 0;
  [[nodiscard]] virtual const SolveInfo& solve_info() const = 0;
};

/// The backend named by options.backend. Throws ConfigError for an unknown name or a backend missing from this
/// build, naming the value and the available backends.
[[nodiscard]] std::unique_ptr<SpdSolver> make_spd_solver(const SolverOptions& options);

/// Names of the backends this build has, default first.
[[nodiscard]] std::vector<std::string> available_backends();

}  // namespace throng::linalg
