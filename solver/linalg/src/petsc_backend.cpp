// The distributed backend: PETSc KSP over the ranks of PETSc's own communicator, PETSC_COMM_WORLD (MFEM
// linalg/petsc.hpp style: PETSc types stay in this file, options through a per-solver prefix; PETSc ex2.c style:
// every call checked, KSPSetFromOptions last so run-time flags win).
//
// Ranks: PETSC_COMM_WORLD is MPI_COMM_WORLD for a distributed solve and MPI_COMM_SELF in a farm
// (mpi::use_ranks_independently: each rank solves its own jobs alone), so ranks and row ranges come from that
// communicator, never from MPI_COMM_WORLD.
//
// Data layout (petsc_layout.h): the unknowns are renumbered by part: METIS splits the matrix's node graph
// into one part per rank (and each of those into -<prefix>parts_per_rank sub-parts, the subdomains of additive
// Schwarz), parts are dealt to ranks, and each rank owns the contiguous rows of its parts. Each rank inserts
// only its own rows (columns mapped to the part order) into an MPIAIJ matrix, and reads only its own rows of the
// matrices and right-hand sides it is given (owned_columns()): least_squares.h assembles the whole matrix once,
// for the layout, then only this rank's columns, and keeps none of it after the numeric phase. After each
// solve every rank receives the whole solution, back in the caller's order.
//
// Defaults: conjugate gradients with hypre's BoomerAMG (HMIS coarsening, ext+i interpolation, P_max 4, strength
// threshold 0.5; PETSc's GAMG where PETSc has no hypre), one part per rank, the convergence test on the true
// (unpreconditioned) residual for CG (other Krylov methods keep their own norm: MINRES, for one, supports only
// the preconditioned norm), block size and near null space from the caller's hint (GAMG uses them; BoomerAMG
// coarsens the scalar graph). GAMG is `-pc_type gamg`; additive Schwarz on the parts `-pc_type asm -sub_pc_type
// icc -parts_per_rank K` (one subdomain per METIS part, PCASM's overlap 1).
//
// Where the time went (PETSc -log_view, 2 cores shared with other work, load 3-7, so times are rough; iteration
// counts and flops are not): the editing systems are Laplacian-coordinate energies, fourth order along time
// (second differences of second differences), so multigrid needs tens to hundreds of CG iterations at the
// default relative residual 1e-12, each costing a few passes over a matrix of ~90 entries a row.
//   * battlefield edit (configs/edit-battlefield.yaml on configs/sketch-paper.yaml, 16,600 free unknowns, 2 drags
//     = 8 pin-basis coordinates per step): the precompute made 16 CG solves for the basis columns (KSPMatSolve
//     would only loop over them: this PETSc has no block CG, HPDDM), 23 s of a 26 s run on 1 rank. Iterative
//     backends now skip the basis (least_squares.cpp): 1 rank 26 s -> 6 s with GAMG, 2.4 s with BoomerAMG.
//   * CG iterations (step 1 + step 2 of the first drag), same conditions:
//       battlefield        GAMG 173 + 126; GAMG threshold 0.02: 77 + 61 but 3x the setup; unsmoothed
//                          aggregation 220 + 153; BoomerAMG (defaults above) 45 + 26
//       bench_scale 200 agents x 300 frames (120,000 unknowns, held at the first and last frame)
//                          GAMG 312 + 107 (37.8 s a drag); GAMG threshold 0.01: 74 + 50 but 40 s of setup;
//                          BoomerAMG strength 0.5 with hypre's Falgout coarsening 68 + 20 (19.9 s), with
//                          HMIS / ext+i / P_max 4 73 + 19 (16.7 s), one run each; the defaults above, rerun:
//                          72 + 19 (22.9 s a drag on 1 rank, 25.1 s on 2, load 4-5); 1,000 agents
//                          (600,000 unknowns) 77 + 18, 159 s a drag at load 7 (72 s of CPU), 5.7 GB
//   * relative tolerance: 1e-10 instead of 1e-12 saves ~20% of the iterations; the battlefield result then
//     moves 3e-6 m from the direct solve (3.8e-8 m at 1e-12): the default stays 1e-12.
//   * additive Schwarz + ICC (earlier measurements, GAMG era): DIVERGED_ITS on the battlefield at 1 part per rank
//     and on 1 rank at 4 parts; one-level Schwarz has no coarse space, and a drag moves whole paths.
// Two ranks were no faster than one on 2 shared cores: the ranks compete with each other and the rest of the
// machine.
#include "backends.h"
#include "blas_threads.h"
#include "petsc_check.h"
#include "petsc_layout.h"

#include <throng/core/errors.h>

#include <Eigen/QR>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
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

void broadcast_ints(std::vector<int>& data, MPI_Comm comm) {
  int n = static_cast<int>(data.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  data.resize(static_cast<std::size_t>(n));
  MPI_Bcast(data.data(), n, MPI_INT, 0, comm);
}

class PetscSpdSolver final : public SpdSolver {
 public:
  explicit PetscSpdSolver(const SolverOptions& options) : options_(options) {
    if (options_.petsc_prefix.empty() || options_.petsc_prefix.back() != '_') {
      throw ConfigError("solver.petsc_prefix '" + options_.petsc_prefix + "' must end with '_'");
    }
  }

  ~PetscSpdSolver() override { destroy(); }

  [[nodiscard]] std::string name() const override { return "petsc"; }

  // Direct only when the user made the KSP a single application of a factorising preconditioner
  // (-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps): then extra columns are cheap.
  [[nodiscard]] bool is_direct() const override { return preonly_; }

  // The caller's indices of this rank's rows (its METIS parts), increasing; empty on one rank (all of them).
  [[nodiscard]] std::vector<Eigen::Index> owned_columns() const override {
    if (ranks_ <= 1) return {};
    std::vector<Eigen::Index> owned;
    owned.reserve(static_cast<std::size_t>(end_ - begin_));
    for (PetscInt row = begin_; row < end_; ++row) owned.push_back(old_of(row));
    std::sort(owned.begin(), owned.end());
    return owned;
  }

  void set_near_null_space(const Eigen::Ref<const Eigen::MatrixXd>& modes, int block_size) override {
    block_size_ = std::max(1, block_size);
    if (modes.cols() == 0) {
      near_null_.resize(0, 0);
      return;
    }
    // PETSc wants orthonormal vectors (the part order only permutes rows: still orthonormal).
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(modes);
    near_null_ = qr.householderQ() * Eigen::MatrixXd::Identity(modes.rows(), modes.cols());
  }

  void analyze(const SparseMatrix& matrix) override {
    if (matrix.rows() != matrix.cols()) throw std::invalid_argument("SpdSolver: the matrix is not square");
    destroy();
    const MPI_Comm comm = PETSC_COMM_WORLD;
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &ranks_);
    n_ = static_cast<PetscInt>(matrix.rows());
    const int bs = (block_size_ > 1 && n_ % block_size_ == 0) ? block_size_ : 1;

    // The user's options first: parts_per_rank decides the layout.
    if (!options_.petsc_options.empty()) {
      THRONG_PETSC_CHECK(PetscOptionsInsertString(nullptr, prefixed(options_.petsc_options, options_.petsc_prefix).c_str()));
    }
    PetscInt parts_per_rank = 1;
    PetscBool given = PETSC_FALSE;
    THRONG_PETSC_CHECK(PetscOptionsGetInt(nullptr, options_.petsc_prefix.c_str(), "-parts_per_rank", &parts_per_rank, &given));
    if (parts_per_rank < 1 || parts_per_rank > 100000) {
      throw ConfigError("PETSc option -" + options_.petsc_prefix + "parts_per_rank " + std::to_string(parts_per_rank) +
                        " is outside [1, 100000]");
    }

    // The part layout, made on rank 0 and sent to the others (every rank then holds the same numbering).
    if (rank_ == 0) layout_ = petsc::part_layout(matrix, bs, ranks_, static_cast<int>(parts_per_rank));
    if (ranks_ > 1) {
      broadcast_ints(layout_.new_of, comm);
      broadcast_ints(layout_.rank_begin, comm);
      broadcast_ints(layout_.part_begin, comm);
      broadcast_ints(layout_.part_rank, comm);
      layout_.old_of.assign(layout_.new_of.size(), 0);
      for (std::size_t i = 0; i < layout_.new_of.size(); ++i) layout_.old_of[static_cast<std::size_t>(layout_.new_of[i])] = static_cast<int>(i);
    }
    begin_ = layout_.rank_begin[static_cast<std::size_t>(rank_)];
    end_ = layout_.rank_begin[static_cast<std::size_t>(rank_) + 1];

    std::vector<PetscInt> diagonal(static_cast<std::size_t>(end_ - begin_), 0);
    std::vector<PetscInt> off_diagonal(diagonal.size(), 0);
    for (PetscInt row = begin_; row < end_; ++row) {
      // Symmetric: column old(row) holds row old(row).
      for (SparseMatrix::InnerIterator it(matrix, old_of(row)); it; ++it) {
        const PetscInt column = new_of(it.row());
        const bool local = column >= begin_ && column < end_;
        ++(local ? diagonal : off_diagonal)[static_cast<std::size_t>(row - begin_)];
      }
    }
    THRONG_PETSC_CHECK(MatCreate(comm, &matrix_));
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

    THRONG_PETSC_CHECK(KSPCreate(comm, &ksp_));
    THRONG_PETSC_CHECK(KSPSetOptionsPrefix(ksp_, options_.petsc_prefix.c_str()));
    THRONG_PETSC_CHECK(KSPSetType(ksp_, KSPCG));
    PC pc = nullptr;
    THRONG_PETSC_CHECK(KSPGetPC(ksp_, &pc));
#ifdef PETSC_HAVE_HYPRE
    THRONG_PETSC_CHECK(PCSetType(pc, PCHYPRE));
    set_default_options();
#else
    THRONG_PETSC_CHECK(PCSetType(pc, PCGAMG));
#endif
    THRONG_PETSC_CHECK(KSPSetTolerances(ksp_, options_.relative_tolerance, 1e-300, PETSC_DEFAULT,
                                        static_cast<PetscInt>(options_.max_iterations)));
    set_from_options();
    KSPType type = nullptr;
    THRONG_PETSC_CHECK(KSPGetType(ksp_, &type));
    PetscBool preonly = PETSC_FALSE;
    THRONG_PETSC_CHECK(PetscStrcmp(type, KSPPREONLY, &preonly));
    preonly_ = preonly == PETSC_TRUE;
    set_subdomains(pc);
    info_ = {};
  }

  void factorize(const SparseMatrix& matrix) override {
    if (matrix_ == nullptr || matrix.rows() != n_) analyze(matrix);
    const BlasThreadScope threads(options_.blas_threads);
    THRONG_PETSC_CHECK(MatZeroEntries(matrix_));
    std::vector<PetscInt> columns;
    std::vector<PetscScalar> values;
    // A diagonal entry ≤ 0 cannot be SPD (an unknown no row of the objective reaches): say so before the Krylov
    // method turns it into NaN. The smallest such unknown over all ranks, so every rank throws together.
    int bad = std::numeric_limits<int>::max();
    for (PetscInt row = begin_; row < end_; ++row) {
      columns.clear();
      values.clear();
      const Eigen::Index old = old_of(row);
      double diagonal = 0;
      for (SparseMatrix::InnerIterator it(matrix, old); it; ++it) {
        columns.push_back(new_of(it.row()));
        values.push_back(it.value());
        if (it.row() == old) diagonal = it.value();
      }
      if (!(diagonal > 0)) bad = std::min(bad, static_cast<int>(old));
      THRONG_PETSC_CHECK(MatSetValues(matrix_, 1, &row, static_cast<PetscInt>(columns.size()), columns.data(),
                                      values.data(), INSERT_VALUES));
    }
    THRONG_PETSC_CHECK(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY));
    THRONG_PETSC_CHECK(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY));
    if (ranks_ > 1) MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
    if (bad != std::numeric_limits<int>::max()) {
      throw SingularMatrixError("PETSc: the matrix is singular or not positive definite: row " + std::to_string(bad) +
                                " has no positive diagonal entry", bad);
    }
    attach_near_null_space();
    THRONG_PETSC_CHECK(KSPSetOperators(ksp_, matrix_, matrix_));
    THRONG_PETSC_CHECK(KSPSetUp(ksp_));

    KSPType ksp_type = nullptr;
    PCType pc_type = nullptr;
    PC pc = nullptr;
    THRONG_PETSC_CHECK(KSPGetType(ksp_, &ksp_type));
    THRONG_PETSC_CHECK(KSPGetPC(ksp_, &pc));
    THRONG_PETSC_CHECK(PCGetType(pc, &pc_type));
    const int parts = static_cast<int>(layout_.part_rank.size());
    info_.method = std::string("PETSc ") + (ksp_type ? ksp_type : "?") + " + " + (pc_type ? pc_type : "?") + " on " +
                   std::to_string(ranks_) + (ranks_ == 1 ? " rank" : " ranks") +
                   (parts > 1 ? " (" + std::to_string(parts) + " METIS parts)" : "");
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
  [[nodiscard]] PetscInt new_of(Eigen::Index old) const {
    return layout_.new_of.empty() ? static_cast<PetscInt>(old) : layout_.new_of[static_cast<std::size_t>(old)];
  }
  [[nodiscard]] Eigen::Index old_of(PetscInt row) const {
    return layout_.old_of.empty() ? row : layout_.old_of[static_cast<std::size_t>(row)];
  }

  // BoomerAMG's settings for these systems (see the measurements at the top), each only where the user's options
  // (PETSC_OPTIONS, solver.petsc_options) do not give it: HMIS coarsening with extended+i interpolation of at
  // most 4 entries a row, the usual way to keep hypre's coarse operators sparse, and a strength threshold of 0.5
  // (battlefield: 0.25 took 2.2 s, 0.5 1.2 s for the same iteration counts).
  void set_default_options() {
    const std::pair<const char*, const char*> defaults[] = {{"pc_hypre_type", "boomeramg"},
                                                            {"pc_hypre_boomeramg_coarsen_type", "HMIS"},
                                                            {"pc_hypre_boomeramg_interp_type", "ext+i"},
                                                            {"pc_hypre_boomeramg_P_max", "4"},
                                                            {"pc_hypre_boomeramg_strong_threshold", "0.5"}};
    for (const auto& [key, value] : defaults) {
      const std::string name = "-" + options_.petsc_prefix + key;
      PetscBool given = PETSC_FALSE;
      THRONG_PETSC_CHECK(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &given));
      if (!given) THRONG_PETSC_CHECK(PetscOptionsSetValue(nullptr, name.c_str(), value));
    }
  }

  // KSPSetFromOptions with the user's options (PETSC_OPTIONS and solver.petsc_options): an unknown type or a
  // malformed value there is the user's configuration, not a numerical failure. Then the norm: CG tests the
  // true residual unless the user chose a norm; other methods keep their default.
  void set_from_options() {
    try {
      THRONG_PETSC_CHECK(KSPSetFromOptions(ksp_));
    } catch (const NumericalError& e) {
      throw ConfigError(std::string("the PETSc options (solver.petsc_options '") + options_.petsc_options +
                        "', PETSC_OPTIONS, prefix " + options_.petsc_prefix + ") are not valid: " + e.what());
    }
    KSPType type = nullptr;
    THRONG_PETSC_CHECK(KSPGetType(ksp_, &type));
    PetscBool norm_given = PETSC_FALSE;
    THRONG_PETSC_CHECK(PetscOptionsHasName(nullptr, options_.petsc_prefix.c_str(), "-ksp_norm_type", &norm_given));
    PetscBool cg = PETSC_FALSE;
    THRONG_PETSC_CHECK(PetscStrcmp(type, KSPCG, &cg));
    if (cg && !norm_given) THRONG_PETSC_CHECK(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED));
  }

  // Additive Schwarz on the parts: this rank's parts are its subdomains (PCASM's overlap then extends each).
  void set_subdomains(PC pc) {
    PetscBool asm_pc = PETSC_FALSE;
    THRONG_PETSC_CHECK(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCASM, &asm_pc));
    if (!asm_pc) return;
    std::vector<IS> subdomains;
    for (std::size_t p = 0; p < layout_.part_rank.size(); ++p) {
      if (layout_.part_rank[p] != rank_) continue;
      IS is = nullptr;
      THRONG_PETSC_CHECK(ISCreateStride(PETSC_COMM_SELF, layout_.part_begin[p + 1] - layout_.part_begin[p],
                                        layout_.part_begin[p], 1, &is));
      subdomains.push_back(is);
    }
    if (!subdomains.empty()) {
      THRONG_PETSC_CHECK(PCASMSetLocalSubdomains(pc, static_cast<PetscInt>(subdomains.size()), subdomains.data(), nullptr));
    }
    for (IS& is : subdomains) THRONG_PETSC_CHECK(ISDestroy(&is));
  }

  void solve_columns(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> solution, bool from_guess) {
    assert(ksp_ != nullptr && "factorize() before solve()");
    const BlasThreadScope threads(options_.blas_threads);
    solve_info_ = {};
    for (Eigen::Index c = 0; c < rhs.cols(); ++c) {
      PetscScalar* local = nullptr;
      THRONG_PETSC_CHECK(VecGetArrayWrite(b_, &local));
      for (PetscInt i = begin_; i < end_; ++i) local[i - begin_] = rhs(old_of(i), c);
      THRONG_PETSC_CHECK(VecRestoreArrayWrite(b_, &local));
      if (from_guess) {
        THRONG_PETSC_CHECK(VecGetArrayWrite(x_, &local));
        for (PetscInt i = begin_; i < end_; ++i) local[i - begin_] = solution(old_of(i), c);
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
      for (PetscInt i = 0; i < n_; ++i) solution(i, c) = all[new_of(i)];
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
      for (PetscInt i = begin_; i < end_; ++i) local[i - begin_] = near_null_(old_of(i), k);
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
    PetscBool finalised = PETSC_FALSE;
    PetscFinalized(&finalised);
    if (finalised) return;  // PETSc already finalised at exit: nothing left to free
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
  bool preonly_ = false;
  int rank_ = 0;
  int ranks_ = 1;
  petsc::Layout layout_;
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
