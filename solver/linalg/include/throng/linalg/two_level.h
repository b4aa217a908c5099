// A two-level preconditioner for complex Hermitian positive definite systems whose unknowns fall into chains
// that are strongly coupled along the chain and smoothly across chains: the space-time editing systems, where a
// chain is one agent's positions over time (temporal features couple two samples deep) and agents are coupled
// by formation features that the deformation keeps smooth in space.
//
//  * Smoother S: block Jacobi over given groups of unknowns. Each group's principal submatrix is factorised
//    exactly (LLᴴ in band storage, its half-bandwidth read off the pattern: 2 for an agent's samples), so what
//    couples along a chain is solved exactly; S is damped by ω = 1/λ_max(S A) (power iteration), which keeps the
//    symmetric V-cycle below positive definite (it needs ω < 2/λ_max).
//  * Coarse space: the columns of a given basis U (#unknowns by #coarse; the editor's: smooth functions over
//    groups of agents and stretches of time), with the Galerkin matrix Uᴴ A U factorised by CHOLMOD (complex
//    supernodal LLᴴ). Columns that are linearly dependent only make the Galerkin matrix singular in directions U
//    maps to zero: a relative 1e-10 on its diagonal lets the factorisation through without changing U Ac⁻¹ Uᴴ.
//  * Applied additively (the default), z = ω S r + U Ac⁻¹ Uᴴ r, or as the symmetric two-level cycle
//    (multiplicative):  z = ω S r;  z += U Ac⁻¹ Uᴴ (r − A z);  z += ω S (r − A z). The multiplicative cycle
//    halves the iterations but costs two more products with A per application; measured on the editing systems
//    (300 agents × 300 samples) the additive one precomputes in 13 % less time and drags in half the time (one
//    iteration per drag either way once solution_history.h has a few drags).
//
// Every kernel runs in parallel over rows, groups or columns with a fixed order of summation (hermitian.h) and
// the coarse factor uses SolverOptions::blas_threads BLAS threads: the same input gives the same bits for any
// thread count. The measurements behind the choices are in docs/commands/edit.md ("Choosing the method").
#pragma once

#include <throng/linalg/hermitian.h>

#include <memory>
#include <vector>

namespace throng::linalg {

/// z = M⁻¹ r for a block of residuals; M Hermitian positive definite. apply() may use workspace of its own, so
/// one preconditioner serves one solve at a time.
class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  virtual void apply(const ComplexBlock& r, ComplexBlock& z) = 0;
};

/// How the two levels are combined (see above).
enum class TwoLevelCycle { additive, multiplicative };

struct TwoLevelOptions {
  TwoLevelCycle cycle = TwoLevelCycle::additive;
  int blas_threads = 1;  ///< BLAS threads for the coarse factorisation and solves (SolverOptions::blas_threads)
};

/// What the setup built, for reports and benchmarks.
struct TwoLevelInfo {
  double damping = 1;               ///< ω
  Eigen::Index coarse_size = 0;     ///< columns of U kept (all-zero columns are dropped)
  double coarse_factor_entries = 0; ///< entries of the coarse Cholesky factor
  std::size_t smoother_entries = 0; ///< complex entries of the band factors
  double setup_seconds = 0;
};

class TwoLevelPreconditioner final : public Preconditioner {
 public:
  /// Factorises the groups' blocks and the Galerkin matrix of `coarse_basis`. A is kept by reference and must
  /// outlive the preconditioner. `groups`: every unknown in exactly one group, each group's unknowns
  /// increasing. Throws std::invalid_argument for groups that do not cover the unknowns exactly once or a basis
  /// of the wrong height; SingularMatrixError when a group's block or the Galerkin matrix is not positive
  /// definite (A is not).
  TwoLevelPreconditioner(const ComplexSparse& A, const std::vector<std::vector<int>>& groups, const ComplexSparse& coarse_basis,
                         const TwoLevelOptions& options = {});
  ~TwoLevelPreconditioner() override;
  TwoLevelPreconditioner(const TwoLevelPreconditioner&) = delete;
  TwoLevelPreconditioner& operator=(const TwoLevelPreconditioner&) = delete;

  void apply(const ComplexBlock& r, ComplexBlock& z) override;

  [[nodiscard]] const TwoLevelInfo& info() const noexcept;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace throng::linalg
