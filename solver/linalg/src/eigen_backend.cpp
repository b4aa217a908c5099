// The default backend: CHOLMOD supernodal Cholesky (through Eigen's CholmodSupport, linked with OpenBLAS), and
// Eigen's SimplicialLDLT when CHOLMOD reports a failure other than lack of memory.
//
// Why supernodal: measured here on a 1,000-agent × 100-frame space-time system, Eigen's SimplicialLDLT
// factorises in ~40 s, a METIS-ordered simplicial LLᵀ in ~19 s, CHOLMOD supernodal in ~1.9 s; the supernodal
// path spends its time in dense BLAS kernels on the separators.
#include "backends.h"

#include <throng/core/errors.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

namespace throng::linalg {
namespace {

// CHOLMOD's 64-bit interface (cholmod_l_*): factors beyond 2^31 entries work on machines with the memory.
using LongMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;

// A factor whose (min/max diagonal)² is below this is treated as singular. Exact arithmetic would give a zero
// pivot; rounding leaves one near ε·‖Q‖, i.e. a ratio near 1e-16 .. 1e-30. Well-posed editing systems of a
// few hundred thousand unknowns measure above 1e-9 (tests/linalg): the threshold sits in between.
constexpr double singular_reciprocal_condition = 1e-13;

// Sets the OpenMP thread count (which OpenBLAS's OpenMP build and CHOLMOD follow) for one scope.
class BlasThreadScope {
 public:
  explicit BlasThreadScope(int threads) {
#ifdef _OPENMP
    previous_ = omp_get_max_threads();
    if (threads > 0) omp_set_num_threads(threads);
#else
    (void)threads;
#endif
  }
  ~BlasThreadScope() {
#ifdef _OPENMP
    omp_set_num_threads(previous_);
#endif
  }
  BlasThreadScope(const BlasThreadScope&) = delete;
  BlasThreadScope& operator=(const BlasThreadScope&) = delete;

 private:
  int previous_ = 1;
};

// Eigen's CHOLMOD supernodal LLᵀ with access to the factor (for its diagonal and permutation).
class SupernodalLlt : public Eigen::CholmodSupernodalLLT<LongMatrix, Eigen::Lower> {
 public:
  SupernodalLlt() { cholmod().print = 0; }  // failures are reported by exceptions, not printed
  [[nodiscard]] const cholmod_factor* factor() const { return this->m_cholmodFactor; }
  [[nodiscard]] double reciprocal_condition() { return cholmod_l_rcond(this->m_cholmodFactor, &cholmod()); }
};

const char* ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    default: return "other";
  }
}

// Bytes of physical memory the kernel says can still be used, or nullopt when unknown.
std::optional<double> available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024.0;
  }
  return std::nullopt;
}

std::string gib(double bytes) {
  std::ostringstream out;
  out.precision(3);
  out << bytes / (1024.0 * 1024.0 * 1024.0) << " GiB";
  return out.str();
}

LongMatrix lower_triangle(const SparseMatrix& matrix) {
  LongMatrix lower(matrix.rows(), matrix.cols());
  Eigen::VectorX<SuiteSparse_long> counts = Eigen::VectorX<SuiteSparse_long>::Zero(matrix.cols());
  for (Eigen::Index j = 0; j < matrix.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) counts[j] += it.row() >= j ? 1 : 0;
  }
  lower.reserve(counts);
  for (Eigen::Index j = 0; j < matrix.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) {
      if (it.row() >= j) lower.insert(it.row(), j) = it.value();
    }
  }
  lower.makeCompressed();
  return lower;
}

class EigenSpdSolver final : public SpdSolver {
 public:
  explicit EigenSpdSolver(const SolverOptions& options) : options_(options) {}

  [[nodiscard]] std::string name() const override { return "eigen"; }

  void analyze(const SparseMatrix& matrix) override {
    check_square(matrix);
    const BlasThreadScope threads(options_.blas_threads);
    llt_ = std::make_unique<SupernodalLlt>();
    ldlt_.reset();
    llt_->analyzePattern(lower_triangle(matrix));
    if (llt_->cholmod().status < CHOLMOD_OK) {
      throw NumericalError("CHOLMOD could not analyse the " + std::to_string(matrix.rows()) + "×" +
                           std::to_string(matrix.rows()) + " system (status " + std::to_string(llt_->cholmod().status) + ")");
    }
    const auto& common = llt_->cholmod();
    info_ = {};
    info_.factor_nonzeros = common.lnz;
    info_.method = std::string("CHOLMOD supernodal LLᵀ (") + ordering_name(common.method[common.selected].ordering) + ")";
    check_memory(matrix.rows());
  }

  void factorize(const SparseMatrix& matrix) override {
    check_square(matrix);
    if (!llt_) analyze(matrix);
    const BlasThreadScope threads(options_.blas_threads);
    ldlt_.reset();
    info_.fallback_reason.clear();
    llt_->factorize(lower_triangle(matrix));
    const int status = llt_->cholmod().status;
    if (status == CHOLMOD_OUT_OF_MEMORY || status == CHOLMOD_TOO_LARGE) {
      throw NumericalError("CHOLMOD ran out of memory factorising the " + std::to_string(matrix.rows()) +
                           "-unknown system (factor of " + std::to_string(static_cast<long long>(info_.factor_nonzeros)) +
                           " entries); use the petsc backend (iterative, distributed over ranks) or a smaller problem");
    }
    if (llt_->info() == Eigen::Success) {
      info_.reciprocal_condition = llt_->reciprocal_condition();
      if (!(info_.reciprocal_condition > singular_reciprocal_condition)) {
        throw SingularMatrixError(singular_message("CHOLMOD", info_.reciprocal_condition), -1);
      }
      return;
    }
    // CHOLMOD broke down at a pivot: try Eigen's LDLᵀ, which tolerates what rounding did to LLᵀ's square roots.
    const auto* factor = llt_->factor();
    const Eigen::Index broke_at = static_cast<Eigen::Index>(factor->minor) < matrix.rows() && factor->Perm != nullptr
                                      ? static_cast<SuiteSparse_long*>(factor->Perm)[factor->minor]
                                      : -1;
    info_.fallback_reason = "CHOLMOD reported the matrix not positive definite at row " + std::to_string(broke_at) +
                            " (status " + std::to_string(status) + "); used Eigen SimplicialLDLT";
    ldlt_ = std::make_unique<Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>>();
    ldlt_->compute(matrix);
    if (ldlt_->info() != Eigen::Success) {
      throw SingularMatrixError("the system is singular: CHOLMOD and Eigen's LDLᵀ both broke down (first at row " +
                                    std::to_string(broke_at) + ")",
                                broke_at);
    }
    const Eigen::VectorXd d = ldlt_->vectorD();
    const double max_d = d.cwiseAbs().maxCoeff();
    Eigen::Index worst = 0;
    const double min_d = d.minCoeff(&worst);
    info_.reciprocal_condition = max_d > 0 ? min_d / max_d : 0;
    info_.method = "Eigen SimplicialLDLT (AMD)";
    info_.factor_nonzeros = static_cast<double>(ldlt_->matrixL().nestedExpression().nonZeros());
    if (!(info_.reciprocal_condition > singular_reciprocal_condition)) {
      const Eigen::Index row = ldlt_->permutationPinv().indices()[worst];
      throw SingularMatrixError(singular_message("LDLᵀ", info_.reciprocal_condition), row);
    }
  }

  void solve(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> solution) override {
    const BlasThreadScope threads(options_.blas_threads);
    if (ldlt_) {
      solution = ldlt_->solve(rhs);
    } else {
      assert(llt_ && "factorize() before solve()");
      solution = llt_->solve(rhs);
      if (llt_->info() != Eigen::Success) throw NumericalError("CHOLMOD's triangular solve failed");
    }
    solve_info_ = {};
  }

  [[nodiscard]] const FactorizationInfo& factorization_info() const override { return info_; }
  [[nodiscard]] const SolveInfo& solve_info() const override { return solve_info_; }

 private:
  static void check_square(const SparseMatrix& matrix) {
    if (matrix.rows() != matrix.cols()) throw std::invalid_argument("SpdSolver: the matrix is not square");
  }

  static std::string singular_message(const char* by, double rcond) {
    std::ostringstream out;
    out << "the system is singular: " << by << " factor's (min/max diagonal)² is " << rcond << " (≤ "
        << singular_reciprocal_condition << "); the constraints and pins leave some unknowns undetermined";
    return out.str();
  }

  // Refuses to start a factorisation the machine cannot hold, before spending minutes on it.
  void check_memory(Eigen::Index n) const {
    const auto* factor = llt_->factor();
    if (factor == nullptr) return;
    // Supernodal factors store xsize doubles (dense blocks with their zero padding) plus integer structure.
    const double needed = static_cast<double>(factor->xsize) * sizeof(double) + 64.0 * static_cast<double>(n);
    const auto available = available_memory_bytes();
    if (available && needed > *available) {
      throw NumericalError("the Cholesky factor of the " + std::to_string(n) + "-unknown system needs " + gib(needed) +
                           " but " + gib(*available) +
                           " are available: use the petsc backend (iterative, distributed over ranks), a shorter "
                           "clip, a coarser sampling or fewer agents");
    }
  }

  SolverOptions options_;
  std::unique_ptr<SupernodalLlt> llt_;
  std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>> ldlt_;
  FactorizationInfo info_;
  SolveInfo solve_info_;
};

}  // namespace

std::unique_ptr<SpdSolver> make_eigen_solver(const SolverOptions& options) {
  return std::make_unique<EigenSpdSolver>(options);
}

}  // namespace throng::linalg
