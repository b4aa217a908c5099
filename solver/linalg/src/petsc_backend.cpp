// The distributed backend: PETSc KSP over the ranks of PETSC_COMM_WORLD (MFEM linalg/petsc.hpp style: PETSc types
// stay in this file, options through a per-solver prefix; PETSc ex2.c style: every call checked,
// KSPSetFromOptions last so run-time flags win).
//
// Data layout: every rank holds the same (replicated) matrix and right-hand sides, as the callers build the
// whole problem on every rank; each rank inserts its own block of rows into an MPIAIJ matrix and receives the
// whole solution after each solve. Defaults: conjugate gradients with PETSc's algebraic multigrid (GAMG), the
// convergence test on the true (unpreconditioned) residual, block size and near null space from the caller's
// hint (see bench/linalg for the measurements behind the choice).
#include "backends.h"
#include "blas_threads.h"
#include "petsc_check.h"

#include <throng/core/errors.h>
#include <throng/linalg/mpi.h>

#include <Eigen/QR>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace throng::linalg {
namespace {

// "-ksp_type cg -pc_type gamg" → "-throng_ksp_type cg -throng_pc_type gamg" (values such as -1e-3 are kept).
std::string prefixed(const std::string& options, const std::string& prefix) {
  std::istringstream in(options);
  std::string token;
  std::string out;
  while (in >> token) {
    if (token.size() > 1 && token[0] == '-' && std::isalpha(static_cast<unsigned char>(token[1]))) {
      token = "-" + prefix + token.substr(1);
    }
    out += (out.empty() ? "" : " ") + token;
  }
  return out;
}

class PetscSpdSolver final : public SpdSolver {
 public:
  explicit PetscSpdSolver(const SolverOptions& options) : options_(options) {
    if (options_.petsc_prefix.empty() || options_.petsc_prefix.back() != '_') {
      throw ConfigError("solver.petsc_prefix '" + options_.petsc_prefix + "' must end with '_'");
    }
    mpi::ensure_initialized();
  }

  ~PetscSpdSolver() override { destroy(); }

  [[nodiscard]] std::string name() const override { return "petsc"; }

  void set_near_null_space(const Eigen::Ref<const Eigen::MatrixXd>& modes, int block_size) override {
    block_size_ = std::max(1, block_size);
    if (modes.cols() == 0) {
      near_null_.resize(0, 0);
      return;
    }
    // PETSc wants orthonormal vectors.
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(modes);
    near_null_ = qr.householderQ() * Eigen::MatrixXd::Identity(modes.rows(), modes.cols());
  }

  void analyze(const SparseMatrix& matrix) override {
    if (matrix.rows() != matrix.cols()) throw std::invalid_argument("SpdSolver: the matrix is not square");
    destroy();
    n_ = static_cast<PetscInt>(matrix.rows());
    const int bs = (block_size_ > 1 && n_ % block_size_ == 0) ? block_size_ : 1;
    // Contiguous blocks of rows per rank, whole nodes of `bs` unknowns each.
    const PetscInt nodes = n_ / bs;
    const int ranks = mpi::size();
    const int me = mpi::rank();
    const PetscInt per = nodes / ranks;
    const PetscInt extra = nodes % ranks;
    begin_ = bs * (me * per + std::min<PetscInt>(me, extra));
    end_ = begin_ + bs * (per + (me < extra ? 1 : 0));

    std::vector<PetscInt> diagonal(static_cast<std::size_t>(end_ - begin_), 0);
    std::vector<PetscInt> off_diagonal(diagonal.size(), 0);
    for (PetscInt row = begin_; row < end_; ++row) {
      // Symmetric: column `row` holds row `row`.
      for (SparseMatrix::InnerIterator it(matrix, row); it; ++it) {
        const bool local = it.row() >= begin_ && it.row() < end_;
        ++(local ? diagonal : off_diagonal)[static_cast<std::size_t>(row - begin_)];
      }
    }
    THRONG_PETSC_CHECK(MatCreate(PETSC_COMM_WORLD, &matrix_));
    THRONG_PETSC_CHECK(MatSetSizes(matrix_, end_ - begin_, end_ - begin_, n_, n_));
    THRONG_PETSC_CHECK(MatSetType(matrix_, MATAIJ));
    THRONG_PETSC_CHECK(MatSetBlockSize(matrix_, bs));
    THRONG_PETSC_CHECK(MatSeqAIJSetPreallocation(matrix_, 0, diagonal.data()));
    THRONG_PETSC_CHECK(MatMPIAIJSetPreallocation(matrix_, 0, diagonal.data(), 0, off_diagonal.data()));
    THRONG_PETSC_CHECK(MatSetOption(matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    THRONG_PETSC_CHECK(MatSetOption(matrix_, MAT_SYMMETRIC, PETSC_TRUE));
    THRONG_PETSC_CHECK(MatSetOption(matrix_, MAT_SPD, PETSC_TRUE));
    THRONG_PETSC_CHECK(MatCreateVecs(matrix_, &x_, &b_));
    THRONG_PETSC_CHECK(VecScatterCreateToAll(x_, &to_all_, &x_all_));

    THRONG_PETSC_CHECK(KSPCreate(PETSC_COMM_WORLD, &ksp_));
    THRONG_PETSC_CHECK(KSPSetOptionsPrefix(ksp_, options_.petsc_prefix.c_str()));
    THRONG_PETSC_CHECK(KSPSetType(ksp_, KSPCG));
    PC pc = nullptr;
    THRONG_PETSC_CHECK(KSPGetPC(ksp_, &pc));
    THRONG_PETSC_CHECK(PCSetType(pc, PCGAMG));
    THRONG_PETSC_CHECK(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED));
    THRONG_PETSC_CHECK(KSPSetTolerances(ksp_, options_.relative_tolerance, 1e-300, PETSC_DEFAULT,
                                        static_cast<PetscInt>(options_.max_iterations)));
    if (!options_.petsc_options.empty()) {
      THRONG_PETSC_CHECK(PetscOptionsInsertString(nullptr, prefixed(options_.petsc_options, options_.petsc_prefix).c_str()));
    }
    THRONG_PETSC_CHECK(KSPSetFromOptions(ksp_));
    info_ = {};
  }

  void factorize(const SparseMatrix& matrix) override {
    if (matrix_ == nullptr || matrix.rows() != n_) analyze(matrix);
    const BlasThreadScope threads(options_.blas_threads);
    THRONG_PETSC_CHECK(MatZeroEntries(matrix_));
    std::vector<PetscInt> columns;
    std::vector<PetscScalar> values;
    for (PetscInt row = begin_; row < end_; ++row) {
      columns.clear();
      values.clear();
      for (SparseMatrix::InnerIterator it(matrix, row); it; ++it) {
        columns.push_back(static_cast<PetscInt>(it.row()));
        values.push_back(it.value());
      }
      THRONG_PETSC_CHECK(MatSetValues(matrix_, 1, &row, static_cast<PetscInt>(columns.size()), columns.data(),
                                      values.data(), INSERT_VALUES));
    }
    THRONG_PETSC_CHECK(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY));
    THRONG_PETSC_CHECK(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY));
    attach_near_null_space();
    THRONG_PETSC_CHECK(KSPSetOperators(ksp_, matrix_, matrix_));
    THRONG_PETSC_CHECK(KSPSetUp(ksp_));

    KSPType ksp_type = nullptr;
    PCType pc_type = nullptr;
    PC pc = nullptr;
    THRONG_PETSC_CHECK(KSPGetType(ksp_, &ksp_type));
    THRONG_PETSC_CHECK(KSPGetPC(ksp_, &pc));
    THRONG_PETSC_CHECK(PCGetType(pc, &pc_type));
    info_.method = std::string("PETSc ") + (ksp_type ? ksp_type : "?") + " + " + (pc_type ? pc_type : "?") + " on " +
                   std::to_string(mpi::size()) + (mpi::size() == 1 ? " rank" : " ranks");
  }

  void solve(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> solution) override {
    solve_columns(rhs, solution, false);
  }

  void solve_from(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> solution) override {
    solve_columns(rhs, solution, true);
  }

  [[nodiscard]] const FactorizationInfo& factorization_info() const override { return info_; }
  [[nodiscard]] const SolveInfo& solve_info() const override { return solve_info_; }

 private:
  void solve_columns(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> solution, bool from_guess) {
    assert(ksp_ != nullptr && "factorize() before solve()");
    const BlasThreadScope threads(options_.blas_threads);
    solve_info_ = {};
    for (Eigen::Index c = 0; c < rhs.cols(); ++c) {
      PetscScalar* local = nullptr;
      THRONG_PETSC_CHECK(VecGetArrayWrite(b_, &local));
      for (PetscInt i = begin_; i < end_; ++i) local[i - begin_] = rhs(i, c);
      THRONG_PETSC_CHECK(VecRestoreArrayWrite(b_, &local));
      if (from_guess) {
        THRONG_PETSC_CHECK(VecGetArrayWrite(x_, &local));
        for (PetscInt i = begin_; i < end_; ++i) local[i - begin_] = solution(i, c);
        THRONG_PETSC_CHECK(VecRestoreArrayWrite(x_, &local));
      } else {
        THRONG_PETSC_CHECK(VecSet(x_, 0.0));
      }
      THRONG_PETSC_CHECK(KSPSetInitialGuessNonzero(ksp_, from_guess ? PETSC_TRUE : PETSC_FALSE));
      THRONG_PETSC_CHECK(KSPSolve(ksp_, b_, x_));

      KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
      PetscInt iterations = 0;
      PetscReal residual = 0;
      PetscReal rhs_norm = 0;
      THRONG_PETSC_CHECK(KSPGetConvergedReason(ksp_, &reason));
      THRONG_PETSC_CHECK(KSPGetIterationNumber(ksp_, &iterations));
      THRONG_PETSC_CHECK(KSPGetResidualNorm(ksp_, &residual));
      THRONG_PETSC_CHECK(VecNorm(b_, NORM_2, &rhs_norm));
      const double relative = rhs_norm > 0 ? residual / rhs_norm : 0.0;
      solve_info_.iterations = std::max<int>(solve_info_.iterations, static_cast<int>(iterations));
      solve_info_.relative_residual = std::max(solve_info_.relative_residual, relative);
      if (reason < 0) {
        std::ostringstream message;
        message << info_.method << " did not converge (" << KSPConvergedReasons[reason] << " after " << iterations
                << " iterations, relative residual " << relative << ", asked " << options_.relative_tolerance << ")";
        if (reason == KSP_DIVERGED_INDEFINITE_PC || reason == KSP_DIVERGED_INDEFINITE_MAT ||
            reason == KSP_DIVERGED_BREAKDOWN) {
          throw SingularMatrixError(message.str() + ": the system is singular or not positive definite", -1);
        }
        throw NumericalError(message.str() + "; raise solver.max_iterations or loosen solver.relative_tolerance");
      }

      THRONG_PETSC_CHECK(VecScatterBegin(to_all_, x_, x_all_, INSERT_VALUES, SCATTER_FORWARD));
      THRONG_PETSC_CHECK(VecScatterEnd(to_all_, x_, x_all_, INSERT_VALUES, SCATTER_FORWARD));
      const PetscScalar* all = nullptr;
      THRONG_PETSC_CHECK(VecGetArrayRead(x_all_, &all));
      for (PetscInt i = 0; i < n_; ++i) solution(i, c) = all[i];
      THRONG_PETSC_CHECK(VecRestoreArrayRead(x_all_, &all));
    }
  }

  void attach_near_null_space() {
    if (near_null_.cols() == 0 || near_null_.rows() != n_) return;
    std::vector<Vec> vectors(static_cast<std::size_t>(near_null_.cols()), nullptr);
    for (Eigen::Index k = 0; k < near_null_.cols(); ++k) {
      Vec& v = vectors[static_cast<std::size_t>(k)];
      THRONG_PETSC_CHECK(VecDuplicate(x_, &v));
      PetscScalar* local = nullptr;
      THRONG_PETSC_CHECK(VecGetArrayWrite(v, &local));
      for (PetscInt i = begin_; i < end_; ++i) local[i - begin_] = near_null_(i, k);
      THRONG_PETSC_CHECK(VecRestoreArrayWrite(v, &local));
    }
    MatNullSpace space = nullptr;
    THRONG_PETSC_CHECK(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(vectors.size()),
                                          vectors.data(), &space));
    THRONG_PETSC_CHECK(MatSetNearNullSpace(matrix_, space));
    THRONG_PETSC_CHECK(MatNullSpaceDestroy(&space));
    for (Vec& v : vectors) THRONG_PETSC_CHECK(VecDestroy(&v));
  }

  void destroy() noexcept {
    if (!mpi::is_initialized()) return;  // PETSc already finalised at exit: nothing left to free
    KSPDestroy(&ksp_);
    VecScatterDestroy(&to_all_);
    VecDestroy(&x_all_);
    VecDestroy(&x_);
    VecDestroy(&b_);
    MatDestroy(&matrix_);
  }

  SolverOptions options_;
  Eigen::MatrixXd near_null_;
  int block_size_ = 1;
  PetscInt n_ = 0;
  PetscInt begin_ = 0;
  PetscInt end_ = 0;
  Mat matrix_ = nullptr;
  KSP ksp_ = nullptr;
  Vec x_ = nullptr;
  Vec b_ = nullptr;
  Vec x_all_ = nullptr;
  VecScatter to_all_ = nullptr;
  FactorizationInfo info_;
  SolveInfo solve_info_;
};

}  // namespace

std::unique_ptr<SpdSolver> make_petsc_solver(const SolverOptions& options) {
  return std::make_unique<PetscSpdSolver>(options);
}

}  // namespace throng::linalg
