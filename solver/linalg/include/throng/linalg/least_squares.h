// Constrained sparse linear least squares, the product's one way to solve
//
//   minimise |W^(1/2) (A x − b)|²   subject to   C x = d   and   x[pinned] = pin values
//
// with a precompute/solve split (libigl min_quad_with_fixed, Eigen analyzePattern/factorize/solve):
//   * pinned unknowns are eliminated: with F the free and P the pinned unknowns and Q = AᵀWA, the free part
//     solves Q_FF x_F = (AᵀW b)_F − Q_FP x_P, and Q_FF is symmetric positive definite when the pins determine
//     the problem (otherwise: NumericalError "singular");
//   * general constraints go through the Schur complement S = C_F Q_FF⁻¹ C_Fᵀ on the existing factorisation:
//       x0 = Q_FF⁻¹ r,   S λ = C_F x0 − (d − C_P x_P),   x_F = x0 − Q_FF⁻¹ C_Fᵀ λ,
//     so adding constraints costs one back-substitution per new row, never a refactorisation. Redundant rows
//     (S singular, constraints consistent) are allowed; contradictory rows are a ConstraintError after the solve;
//   * new right-hand sides b, new pin values and new constraint values d only cost back-substitutions.
//
// Stale state is explicit: each mutator marks what it invalidates, precompute() redoes exactly that (and
// solve() calls it when something is stale), and report() counts analyses and factorisations so a caller or
// test can see that a drag did not refactorise.
//
// Shapes (libigl style):
//   A            #rows by #unknowns (sparse)          weights  #rows, ≥ 0
//   b            #rows by #rhs                         pinned   #pinned unknown indices (distinct)
//   pin_values   #pinned by #rhs (in the order given to set_pinned)
//   C            #constraints by #unknowns (sparse)    d        #constraints by #rhs
//   x            #unknowns by #rhs
#pragma once

#include <throng/core/errors.h>
#include <throng/linalg/solver_options.h>
#include <throng/linalg/spd_solver.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace throng::linalg {

/// General constraints that cannot all be met: they contradict each other or the pins. rows() lists the
/// constraint rows (indices into C, in the order they were set and added) that are violated after the solve,
/// so a caller can name them in its own terms.
class ConstraintError : public NumericalError {
 public:
  ConstraintError(const std::string& message, std::vector<Eigen::Index> rows)
      : NumericalError(message), rows_(std::move(rows)) {}
  [[nodiscard]] const std::vector<Eigen::Index>& rows() const noexcept { return rows_; }

 private:
  std::vector<Eigen::Index> rows_;
};

/// What precompute() and solve() did: counts, timings (seconds) and the backend's own report.
struct LeastSquaresReport {
  int analyses = 0;          ///< symbolic analyses so far (new pattern or new pinned set)
  int adopted_analyses = 0;  ///< of which: reused from another solver's (share_analysis), not computed
  int factorizations = 0;    ///< numeric factorisations so far (new values)
  int schur_columns = 0;     ///< back-substitutions spent on Schur complement columns so far
  double analyze_seconds = 0;     ///< last analysis (assembling Q and the symbolic phase)
  double factorize_seconds = 0;   ///< last factorisation
  double schur_seconds = 0;       ///< last Schur complement update
  double basis_seconds = 0;       ///< last pin-basis solve (set_pin_basis)
  int basis_columns = 0;          ///< back-substitutions spent on pin-basis columns so far
  double solve_seconds = 0;       ///< last solve
  Eigen::Index constraint_rank = 0;         ///< rank of the constraints on the free unknowns
  double max_constraint_residual = 0;       ///< max |c·x − d| over unit-length rows, last solve
  FactorizationInfo factorization;
  SolveInfo last_solve;
};

/// The stateful solver. Movable, not copyable; one instance per problem (per rank when the backend is distributed).
class ConstrainedLeastSquares {
 public:
  explicit ConstrainedLeastSquares(const SolverOptions& options = {});
  ~ConstrainedLeastSquares();
  ConstrainedLeastSquares(ConstrainedLeastSquares&&) noexcept;
  ConstrainedLeastSquares& operator=(ConstrainedLeastSquares&&) noexcept;
  ConstrainedLeastSquares(const ConstrainedLeastSquares&) = delete;
  ConstrainedLeastSquares& operator=(const ConstrainedLeastSquares&) = delete;

  /// The objective. Invalidates everything (new pattern: analysis, factorisation, Schur complement).
  void set_objective(const SparseMatrix& A, const Eigen::Ref<const Eigen::VectorXd>& weights);
  /// The same, taking A over: a caller that needs A no more saves its copy (the largest matrix of the problem:
  /// ~1.7 kB per vertex of an editing system, 0.5 GB per step at 1,000 agents × 300 samples).
  void set_objective(SparseMatrix&& A, const Eigen::Ref<const Eigen::VectorXd>& weights);
  /// New row weights for the same A. Invalidates the factorisation and the Schur complement, not the analysis.
  void set_weights(const Eigen::Ref<const Eigen::VectorXd>& weights);
  /// The pinned unknowns (distinct, any order; values come with each solve). Invalidates everything.
  void set_pinned(std::vector<Eigen::Index> pinned);
  /// Pin values given as coordinates in a basis: x[pinned] = B u, B #pinned by #coordinates (rows in the order
  /// of set_pinned), u passed to solve_in_basis(). With a direct backend (SpdSolver::is_direct) precompute()
  /// then also solves Q_FF Z = Q_FP B (#coordinates back-substitutions, one block), and every solve_in_basis()
  /// whose b is the previous one's costs no back-substitution at all: x_F = Q_FF⁻¹ r_b − Z u (r_b = (AᵀW b)_F,
  /// cached). For rigid drags u is a handful of numbers per drag (cos θ, sin θ, translation): the per-drag cost
  /// of the editor's step 1. With an iterative backend each column of Z would be a whole Krylov solve, so Z is
  /// not computed: solve_in_basis() is solve() with pin values B u, started from the previous solution. Nor is
  /// it for more than max_basis_columns coordinates (Z holds #free × #coordinates doubles and costs as many
  /// back-substitutions: worth it for the few coordinates of rigid drags, not for hundreds of individually
  /// placed pins, whose drag then costs one back-substitution more). An empty B (0 columns) removes the basis.
  /// A B whose rows are not the pinned unknowns is std::invalid_argument at precompute(). Invalidates Z only.
  void set_pin_basis(const SparseMatrix& basis);
  static constexpr Eigen::Index max_basis_columns = 64;
  /// Whether precompute() solves for Z (a basis of at most max_basis_columns columns on a direct backend), so
  /// that solve_in_basis() with an unchanged b costs no back-substitution.
  [[nodiscard]] bool precomputes_basis() const;

  /// Replaces the general constraints. Invalidates the Schur complement only.
  void set_constraints(const SparseMatrix& C);
  /// Appends constraint rows: costs one back-substitution per new row, the factorisation is kept.
  void add_constraints(const SparseMatrix& C);
  /// Removes every general constraint (keeps the factorisation).
  void clear_constraints();
  /// Near-null-space hint for multigrid backends (#unknowns by #modes, see SpdSolver), restricted to the free
  /// unknowns; block_size unknowns per node (kept when the pins take or leave whole nodes, else 1).
  /// Invalidates the analysis.
  void set_near_null_space(const Eigen::Ref<const Eigen::MatrixXd>& modes, int block_size);

  /// Declares that A acts on interleaved (x, y) pairs of unknowns through complex scalars (every 2×2 block of
  /// each pair of rows is [[a, −b], [b, a]]), so AᵀWA is complex Hermitian in real form and the backend may
  /// factor it in complex arithmetic. Kept only when the pins take or leave whole pairs. Invalidates the analysis.
  void set_complex_pairs(bool complex_pairs);

  /// Assembles Q and runs the symbolic analysis if stale (the first part of precompute()).
  void analyze();

  /// Lets this solver's analyses reuse `other`'s (SpdSolver::adopt_analysis) when its Q_FF has the pattern of
  /// other's: two objectives over one graph with the same pins analyse once. `other` must outlive this solver
  /// and be analysed first (analyze()); before other's numeric factorisation the reuse copies the symbolic
  /// factor only. nullptr stops it.
  void share_analysis(const ConstrainedLeastSquares* other);

  /// Redoes what the mutators made stale: assemble Q and analyse, factorise, extend the Schur complement.
  /// Throws NumericalError when Q_FF is singular (the pins do not determine x).
  void precompute();

  /// Solves for #rhs right-hand sides at once (see the shapes above). Calls precompute() if anything is stale.
  /// Throws ConstraintError when the constraints cannot be met.
  [[nodiscard]] Eigen::MatrixXd solve(const Eigen::Ref<const Eigen::MatrixXd>& b,
                                      const Eigen::Ref<const Eigen::MatrixXd>& pin_values,
                                      const Eigen::Ref<const Eigen::MatrixXd>& d);

  /// As solve(), with the pin values B u of set_pin_basis() (u: #coordinates by #rhs). Same result as solve()
  /// with pin_values = B u up to rounding; the same calls give the same bits.
  [[nodiscard]] Eigen::MatrixXd solve_in_basis(const Eigen::Ref<const Eigen::MatrixXd>& b,
                                               const Eigen::Ref<const Eigen::MatrixXd>& coordinates,
                                               const Eigen::Ref<const Eigen::MatrixXd>& d);

  [[nodiscard]] Eigen::Index unknowns() const noexcept;
  [[nodiscard]] Eigen::Index constraints() const noexcept;
  [[nodiscard]] const std::vector<Eigen::Index>& pinned() const noexcept;
  /// True when solve() would not need precompute().
  [[nodiscard]] bool is_ready() const noexcept;
  [[nodiscard]] const LeastSquaresReport& report() const noexcept;
  [[nodiscard]] const SolverOptions& options() const noexcept;

 private:
  Eigen::MatrixXd solve_any(const Eigen::Ref<const Eigen::MatrixXd>& b, const Eigen::Ref<const Eigen::MatrixXd>& pins,
                            const Eigen::Ref<const Eigen::MatrixXd>& d, bool in_basis);

  struct State;
  std::unique_ptr<State> state_;
};

/// One-off: the same problem solved once (builds, precomputes and solves a ConstrainedLeastSquares).
/// Empty C means no general constraints (d must then have 0 rows).
[[nodiscard]] Eigen::MatrixXd solve_least_squares(const SparseMatrix& A, const Eigen::Ref<const Eigen::VectorXd>& weights,
                                                  const Eigen::Ref<const Eigen::MatrixXd>& b,
                                                  const std::vector<Eigen::Index>& pinned,
                                                  const Eigen::Ref<const Eigen::MatrixXd>& pin_values,
                                                  const SparseMatrix& C, const Eigen::Ref<const Eigen::MatrixXd>& d,
                                                  const SolverOptions& options = {});

}  // namespace throng::linalg
